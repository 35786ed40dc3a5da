// Sheet files: a variational sheet saved exactly — its shape, the spans of every layer, the
// unknowns with their current and rest control points — so a designed surface can be read
// back and the design continued. The format ("fairshape-sheet", version 1) is line-oriented
// text, one record per line; configs/README.md, "Sheet files", documents it.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

#include "fairshape/bspline/variational_sheet.h"

namespace fairshape::bspline {

inline constexpr const char* kSheetFormatName = "fairshape-sheet";
inline constexpr int kSheetFormatVersion = 1;
//! The file name extension of sheet files.
inline constexpr const char* kSheetFileExtension = ".sheet";

//! Writes the sheet in the current format. Every double is printed in its shortest form that
//! reads back to the same bits. \throw OutputError for a non-finite control point.
void write_sheet(std::ostream& out, const VariationalSheet& sheet);
//! write_sheet into `path`, atomically (a reader never sees half a file).
//! \throw OutputError when the file cannot be written.
void save_sheet(const VariationalSheet& sheet, const std::string& path);

//! The sheet a file's text describes; `name` is the file name used in messages.
//! \throw ParseError ("name:line: problem") for anything but a well-formed file of a version
//! this build reads: unknown or misplaced keys, wrong counts, non-finite numbers, spans outside
//! their layer's grid or not nested in the layer below, unknowns the layers do not define.
VariationalSheet parse_sheet(std::string_view text, const std::string& name);
//! parse_sheet of the file at `path`. \throw IOError for a missing or unreadable file.
VariationalSheet load_sheet(const std::string& path);

}  // namespace fairshape::bspline
