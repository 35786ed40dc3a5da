// Sheet files in sheet runs (format: bspline/sheet_file.h): a `sheets:` entry that starts from
// a saved sheet (`file:`), and the sheets every run saves, so a design can be continued.
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"

namespace fairshape {

//! A `sheets:` entry with `file:` — name, file (resolved like every input file), refine. The
//! file is read now, so a missing or malformed one stops the sweep before anything runs.
//! \throw InvalidConfig naming the key, also for a shape key (spans, degree, geometry, size,
//! origin, u_axis, v_axis): the shape comes from the file.
SheetSpec read_sheet_from_file(Config& c, const std::vector<std::string>& search_dirs);

//! The sheet an entry starts from, before its `refine:`: the file's (its coefficients and rest
//! shape), or the placed plane or cylinder.
bspline::VariationalSheet initial_sheet(const SheetSpec& s);

//! The resolved paths of the sheet files a run reads (validation reports them as inputs).
std::vector<std::string> sheet_input_files(const SheetRunSpec& spec);

//! Saves every sheet as sheets/<run_id>_<sheet>.sheet (step < 0: the final state) or
//! sheets/<run_id>_step<k>_<sheet>.sheet, inside out.dir whatever the sheet's name.
//! \throw OutputError when a file cannot be written.
void write_sheet_files(const RunOutputs& out, const std::vector<SheetSpec>& specs,
                       const std::vector<bspline::VariationalSheet>& sheets, int step);

}  // namespace fairshape
