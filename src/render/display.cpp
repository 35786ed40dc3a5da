#include "fairshape/render/display.h"

#include <X11/Xlib.h>

#include <cstdlib>

namespace fairshape::render {

bool display_available() {
  const char* d = std::getenv("DISPLAY");
  if (!d || !*d) return false;
  Display* x = XOpenDisplay(d);
  if (!x) return false;
  XCloseDisplay(x);
  return true;
}

}  // namespace fairshape::render
