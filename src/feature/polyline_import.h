// Feature curves drawn elsewhere (a modelling tool, a script) and brought in as a file of
// points: an .obj polyline (`v` and `l` lines) or a plain list of "x y z" lines.
#pragma once

#include <string>

#include "fairshape/mesh/polyline.h"

namespace fairshape::feature {

//! The curve in `path`: the first `l` polyline of an .obj file (closed when it ends on its first
//! vertex), else one point per line ("x y z", blank lines and '#' comments skipped; closed when
//! the last point repeats the first, which is then dropped).
//! \throw IOError, ParseError (file and line) for an unreadable file or a line that is not
//! three finite numbers; InvalidInput for fewer than 2 points.
Polyline read_curve_points(const std::string& path);

}  // namespace fairshape::feature
