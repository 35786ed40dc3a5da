// A figure: one or more panels side by side (an input panel, result panels), one camera and
// one colour range shared by all of them, a title, a label per panel and a colour bar, written
// as one PNG. Two lights (a key and a fill) shade every panel alike.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fairshape/render/camera.h"
#include "fairshape/render/scene.h"

namespace fairshape::render {

enum class Background { White, Transparent };
const NameTable<Background>& background_names();  // white | transparent

struct FigureSpec {
  std::vector<std::string> panels;  // load_render_source specs, in reading order
  std::vector<std::string> labels;  // one per panel, or none
  std::string rest;                 // an input panel before them, uncoloured (e.g. the rest shape)
  std::string rest_label = "input";
  std::string title;
  SourceChoice choice;
  Colouring colouring;
  std::string colour_label;  // the colour bar's label (default: the array and component)
  std::optional<std::pair<double, double>> range;  // default: over every panel
  SurfaceStyle style;
  bool overlays = true;                  // a run's constraints overlay, when it has one
  std::vector<std::string> extra_overlays;  // drawn over every panel (e.g. feature curves)
  ViewSpec view;
  //! Focus on the first panel's moved handles and normal targets (its overlay), framing them
  //! with a margin; --radius still sets the frame when given.
  bool focus_on_constraints = false;
  int panel_width = 1200, panel_height = 900, columns = 0;  // 0: one row
  Background background = Background::White;
  //! Non-empty: also write the camera and each panel's world-to-pixel projection there (JSON),
  //! to reuse the view or to find a point in the image.
  std::string camera_path;
};

//! \throw InvalidInput / IOError naming the input or the option; nothing is written then.
void render_figure(const FigureSpec& spec, const std::string& png_path);

}  // namespace fairshape::render
