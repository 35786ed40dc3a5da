// Internal: what a VTK XML file declares, checked before VTK reads it. VTK allocates what the
// XML says (element counts, components per tuple, compressed block sizes) before it looks at
// the data, so a few hundred corrupt or hostile bytes can ask it for terabytes.
#pragma once

#include <string>
#include <vector>

namespace fairshape::io::internal {

//! The bytes of the VTK XML file at `path`, its XML parsed (attributes read whatever their
//! quoting and spacing) and checked: every NumberOf… count, every array's components × tuples,
//! every appended or inline binary array's header against the bytes the file holds.
//! `pieces`, when given, receives the `file` attributes (a multiblock's pieces), as written.
//! \throw IOError (ParseError with the line where one is known) naming the file.
std::string checked_vtk_text(const std::string& path, std::vector<std::string>* pieces = nullptr);

}  // namespace fairshape::io::internal
