// Debian's VTK renders only through an X server (no EGL, no OSMesa).
#pragma once

namespace fairshape::render {

//! Whether $DISPLAY names an X server that accepts a connection.
bool display_available();

}  // namespace fairshape::render
