#include "fairshape/render/figure.h"

#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkPointData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "fairshape/core/atomic_file.h"
#include "fairshape/io/constraint_overlay.h"
#include "fairshape/io/json_io.h"
#include "fairshape/core/error.h"
#include "fairshape/render/display.h"
#include "fairshape/render/overlay.h"

namespace fairshape::render {

const NameTable<Background>& background_names() {
  static const NameTable<Background> t{{Background::White, "white"}, {Background::Transparent, "transparent"}};
  return t;
}

namespace {

constexpr int kTitleHeight = 56, kLabelHeight = 40, kColourBarWidth = 190;

// A key light above right of the camera and a dimmer fill from the left: shape reads from
// shading, and no side of the model is black.
void add_lights(vtkRenderer* r) {
  r->AutomaticLightCreationOff();
  vtkNew<vtkLight> key;
  key->SetLightTypeToCameraLight();
  key->SetPosition(0.6, 0.8, 1.0);
  key->SetFocalPoint(0, 0, 0);
  key->SetIntensity(0.85);
  r->AddLight(key);
  vtkNew<vtkLight> fill;
  fill->SetLightTypeToCameraLight();
  fill->SetPosition(-0.8, -0.2, 0.6);
  fill->SetFocalPoint(0, 0, 0);
  fill->SetIntensity(0.35);
  r->AddLight(fill);
}

// Text in window pixels, centred on x, shrunk to fit `width` (and cut with an ellipsis only
// below a legible size).
vtkSmartPointer<vtkTextActor> text(const std::string& s, double x, double y, int width, int size) {
  auto t = vtkSmartPointer<vtkTextActor>::New();
  // A glyph is about 0.55 of the font size wide: the size that fits the panel.
  const int fitting = static_cast<int>(width / (0.55 * std::max<std::size_t>(s.size(), 1)));
  const int font = std::clamp(fitting, 10, size);
  std::string shown = s;
  const std::size_t most = static_cast<std::size_t>(width / (0.55 * font));
  if (shown.size() > most && most > 3) shown = shown.substr(0, most - 3) + "...";
  t->SetInput(shown.c_str());
  vtkTextProperty* p = t->GetTextProperty();
  p->SetFontSize(font);
  p->SetColor(0.1, 0.1, 0.1);
  p->SetJustificationToCentered();
  p->SetVerticalJustificationToCentered();
  t->SetDisplayPosition(static_cast<int>(x), static_cast<int>(y));
  return t;
}

// The colour bar in the strip right of the panels (from pixel x0, `width` wide, of a W-wide window).
vtkSmartPointer<vtkScalarBarActor> colour_bar(vtkScalarsToColors* colours, const std::string& label, int x0, int width, int W) {
  auto bar = vtkSmartPointer<vtkScalarBarActor>::New();
  bar->SetLookupTable(colours);
  bar->SetTitle(label.c_str());
  bar->SetNumberOfLabels(5);
  bar->SetLabelFormat("%-#7.3g");
  bar->SetMaximumWidthInPixels(width - 30);
  bar->SetPosition(static_cast<double>(x0 + 10) / W, 0.1);
  bar->SetWidth(static_cast<double>(width - 20) / W);
  bar->SetHeight(0.8);
  bar->UnconstrainedFontSizeOn();
  for (vtkTextProperty* p : {bar->GetTitleTextProperty(), bar->GetLabelTextProperty()}) {
    p->SetColor(0.1, 0.1, 0.1);
    p->SetFontSize(15);
    p->ItalicOff();
    p->ShadowOff();
    p->BoldOff();
  }
  return bar;
}

std::string default_colour_label(const Colouring& c) {
  if (!c.component_given || c.component == Component::Magnitude) return c.array == "displacement" ? "|displacement|" : c.array;
  if (c.component == Component::Normal) return "normal " + c.array;
  return c.array + " " + std::string(component_names().name(c.component));
}

// The centre and extent of a source's moved handles (where they started too) and normal
// targets in its overlay (null: it has none), as the view's focus.
void focus_on_handles(const RenderSource& source, vtkPolyData* overlay, double diagonal, ViewSpec& view) {
  if (!overlay)
    throw InvalidInput("render: --focus-constraints needs an overlay: " + source.path + " has no " +
                       "<stem>_constraints.vtp beside it");
  vtkDataArray* kind = overlay->GetPointData()->GetArray(kOverlayKind);
  vtkDataArray* offset = overlay->GetPointData()->GetArray(kOverlayOffset);
  std::vector<Vec3> at;  // the handles where they ended and where they started, the normal targets
  for (vtkIdType i = 0; kind && i < overlay->GetNumberOfPoints(); ++i)
    if (const auto k = static_cast<OverlayKind>(static_cast<int>(kind->GetComponent(i, 0)));
        k == OverlayKind::Handle || k == OverlayKind::Normal) {
      double p[3];
      overlay->GetPoint(i, p);
      at.emplace_back(p[0], p[1], p[2]);
      if (k == OverlayKind::Handle && offset) {
        const double* o = offset->GetTuple3(i);
        at.emplace_back(p[0] - o[0], p[1] - o[1], p[2] - o[2]);
      }
    }
  if (at.empty()) throw InvalidInput("render: --focus-constraints: " + source.overlay_path + " has no handle or normal target");
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : at) centre += p / static_cast<double>(at.size());
  double extent = 0;
  for (const Vec3& p : at) extent = std::max(extent, (p - centre).norm());
  view.focused = true;
  view.focus = centre;
  if (!(view.radius > 0)) view.radius = 1.5 * extent + 0.08 * diagonal;
}

// A panel whose pixels are all background shows nothing: the camera looks away from the
// model (a --focus off it, too much --zoom). Refused rather than written as a blank figure.
void require_visible(vtkImageData* image, const std::vector<std::array<int, 4>>& panels, bool transparent) {
  const int comps = image->GetNumberOfScalarComponents();
  const auto* px = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int W = image->GetDimensions()[0];
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const auto& [x0, y0, w, h] = panels[k];
    bool seen = false;
    for (int y = y0; y < y0 + h && !seen; ++y)
      for (int x = x0; x < x0 + w && !seen; ++x) {
        const unsigned char* p = px + (static_cast<std::size_t>(y) * W + x) * comps;
        seen = transparent ? p[3] != 0 : (p[0] < 250 || p[1] < 250 || p[2] < 250);
      }
    if (!seen)
      throw InvalidInput("render: panel " + std::to_string(k + 1) + " shows nothing: the camera looks away from the " +
                         "model (check --focus, --radius, --zoom)");
  }
}

// The camera, and per panel the matrix taking homogeneous world points to normalized device
// coordinates ([-1, 1]², x right, y up) of that panel's rectangle.
void write_camera(vtkCamera* cam, const std::vector<std::array<int, 4>>& panels, int W, int H, const std::string& path) {
  nlohmann::json j;
  double v[3];
  cam->GetPosition(v);
  j["position"] = {v[0], v[1], v[2]};
  cam->GetFocalPoint(v);
  j["focal_point"] = {v[0], v[1], v[2]};
  cam->GetViewUp(v);
  j["view_up"] = {v[0], v[1], v[2]};
  j["view_angle_deg"] = cam->GetViewAngle();
  j["image"] = {W, H};
  for (const auto& p : panels) {
    vtkMatrix4x4* m = cam->GetCompositeProjectionTransformMatrix(static_cast<double>(p[2]) / p[3], -1, 1);
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({m->GetElement(r, 0), m->GetElement(r, 1), m->GetElement(r, 2), m->GetElement(r, 3)});
    j["panels"].push_back({{"pixels_from_bottom_left", {p[0], p[1], p[2], p[3]}}, {"world_to_ndc", rows}});
  }
  write_json(j, path);
}

// What the panels show, loaded: the sources, their scalars (null for an uncoloured panel),
// the scene's bounds and the scalars' range over every panel.
struct Panels {
  std::vector<RenderSource> sources;
  std::vector<vtkSmartPointer<vtkDoubleArray>> scalars;
  double bounds[6] = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  double lo = 1e300, hi = -1e300;
};

Panels load_panels(const std::vector<std::string>& inputs, std::size_t first_coloured, const FigureSpec& spec) {
  Panels out;
  for (const std::string& p : inputs) {
    out.sources.push_back(load_render_source(p, spec.choice));
    double b[6];
    out.sources.back().data->GetBounds(b);
    for (int k = 0; k < 3; ++k) {
      out.bounds[2 * k] = std::min(out.bounds[2 * k], b[2 * k]);
      out.bounds[2 * k + 1] = std::max(out.bounds[2 * k + 1], b[2 * k + 1]);
    }
    if (spec.colouring.array.empty() || out.sources.size() <= first_coloured) {
      out.scalars.emplace_back();
      continue;
    }
    out.scalars.push_back(panel_scalars(out.sources.back().data, spec.colouring, out.sources.back().path));
    double r[2];
    out.scalars.back()->GetRange(r);
    out.lo = std::min(out.lo, r[0]);
    out.hi = std::max(out.hi, r[1]);
  }
  return out;
}

}  // namespace

void render_figure(const FigureSpec& spec, const std::string& png_path) {
  if (spec.panels.empty()) throw InvalidInput("render: no input");
  if (!spec.labels.empty() && spec.labels.size() != spec.panels.size())
    throw InvalidInput("render: " + std::to_string(spec.labels.size()) + " --label for " + std::to_string(spec.panels.size()) +
                       " inputs (give one per input, or none)");
  if (std::filesystem::path(png_path).extension() != ".png") throw InvalidInput("render: " + png_path + ": the output is a .png");
  const std::filesystem::path folder = std::filesystem::absolute(png_path).parent_path();
  if (!std::filesystem::is_directory(folder)) throw IOError("render: the output folder " + folder.string() + " does not exist");
  if (!display_available()) throw IOError("render: no X display (run under xvfb-run, or set DISPLAY)");

  std::vector<std::string> inputs = spec.panels, labels = spec.labels;
  if (!spec.rest.empty()) {
    inputs.insert(inputs.begin(), spec.rest);
    if (!labels.empty()) labels.insert(labels.begin(), spec.rest_label);
  }
  const std::size_t first_coloured = spec.rest.empty() ? 0 : 1;
  const Panels loaded = load_panels(inputs, first_coloured, spec);
  const std::vector<RenderSource>& sources = loaded.sources;
  const std::vector<vtkSmartPointer<vtkDoubleArray>>& scalars = loaded.scalars;
  const double* bounds = loaded.bounds;
  double lo = loaded.lo, hi = loaded.hi;
  // Without --label, panels of runs are labelled by their swept parameters (when each has some).
  if (labels.empty() && inputs.size() > 1 &&
      std::all_of(sources.begin() + static_cast<long>(first_coloured), sources.end(), [](const RenderSource& r) { return !r.parameters.empty(); })) {
    if (!spec.rest.empty()) labels.push_back(spec.rest_label);
    for (std::size_t k = first_coloured; k < sources.size(); ++k) labels.push_back(sources[k].parameters);
  }
  const bool coloured = !spec.colouring.array.empty();
  const ColourMap map = spec.colouring.effective_map();
  if (spec.range) {
    std::tie(lo, hi) = *spec.range;
  } else if (coloured && map == ColourMap::Diverging) {  // centred on zero: the sign reads as the colour's hue
    const double m = std::max(std::abs(lo), std::abs(hi));
    lo = -m;
    hi = m;
  }
  if (coloured && !(hi > lo)) hi = lo + (lo == 0 ? 1 : std::abs(lo) * 1e-6);  // a constant field
  const auto colours = coloured ? colour_transfer(map, lo, hi) : nullptr;
  const double diagonal =
      std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) + std::pow(bounds[5] - bounds[4], 2));

  const int n = static_cast<int>(sources.size());
  const int cols = spec.columns > 0 ? std::min(spec.columns, n) : n, rows = (n + cols - 1) / cols;
  const int w = spec.panel_width, h = spec.panel_height;
  const int label_h = labels.empty() ? 0 : kLabelHeight, title_h = spec.title.empty() ? 0 : kTitleHeight;
  const int bar_w = coloured ? kColourBarWidth : 0;
  const int W = cols * w + bar_w, H = title_h + rows * (h + label_h);
  const bool transparent = spec.background == Background::Transparent;
  // VTK holds about 64 bytes per pixel while it renders and grabs: 8192² pixels in all is 4 GB.
  constexpr long long kMaxPixels = 8192LL * 8192;
  if (static_cast<long long>(W) * H > kMaxPixels)
    throw InvalidInput("render: a " + std::to_string(W) + " x " + std::to_string(H) + " figure is above " +
                       std::to_string(kMaxPixels) + " pixels (about 4 GB while rendering): fewer or smaller panels");

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(W, H);
  window->SetNumberOfLayers(2);
  if (transparent) window->SetAlphaBitPlanes(1);
  vtkNew<vtkCamera> camera;  // shared: every panel seen alike
  vtkNew<vtkRenderer> background, annotations;
  background->SetViewport(0, 0, 1, 1);
  background->SetBackground(1, 1, 1);
  background->SetBackgroundAlpha(transparent ? 0.0 : 1.0);
  window->AddRenderer(background);
  annotations->SetLayer(1);
  annotations->SetViewport(0, 0, 1, 1);
  annotations->PreserveColorBufferOn();  // text over the panels, not over a cleared window
  window->AddRenderer(annotations);
  std::vector<std::array<int, 4>> panels;  // x, y (from the bottom), width, height in pixels
  for (int i = 0; i < n; ++i) {
    const int col = i % cols, row = i / cols;
    const double x0 = static_cast<double>(col * w) / W, x1 = static_cast<double>((col + 1) * w) / W;
    const double top = H - title_h - row * (h + label_h) - label_h;  // the panel's top edge, in pixels
    vtkNew<vtkRenderer> r;
    r->SetViewport(x0, (top - h) / H, x1, top / H);
    panels.push_back({col * w, static_cast<int>(top) - h, w, h});
    r->SetBackground(1, 1, 1);
    r->SetBackgroundAlpha(transparent ? 0.0 : 1.0);
    r->SetActiveCamera(camera);
    add_lights(r);
    const auto k = static_cast<std::size_t>(i);
    for (const auto& prop : panel_props(sources[k], scalars[k], scalars[k] ? colours.Get() : nullptr, lo, hi, spec.style, diagonal))
      r->AddViewProp(prop);
    const RenderSource& src = sources[k];
    // The source's own overlay (read once: it also gives --focus-constraints its handles).
    const bool wanted = spec.overlays || (i == 0 && spec.focus_on_constraints);
    const vtkSmartPointer<vtkPolyData> own = wanted && !src.overlay_path.empty() ? load_overlay(src.overlay_path) : nullptr;
    if (spec.overlays && own)
      for (const auto& prop : overlay_props(own, diagonal, spec.style.overlay_curve_radius)) r->AddViewProp(prop);
    for (const std::string& o : spec.extra_overlays)
      for (const auto& prop : overlay_props(load_overlay(o), diagonal, spec.style.overlay_curve_radius)) r->AddViewProp(prop);
    window->AddRenderer(r);
    if (i == 0) {
      ViewSpec view = spec.view;
      if (spec.focus_on_constraints) focus_on_handles(src, own, diagonal, view);
      if (view.focused && !(view.radius > 0)) view.radius = diagonal / 4;
      place_camera(r, view, bounds);
    }
    if (!labels.empty()) annotations->AddActor2D(text(labels[k], (col + 0.5) * w, top + label_h / 2.0, w - 16, 22));
  }
  if (title_h) annotations->AddActor2D(text(spec.title, W / 2.0, H - title_h / 2.0, W - 24, 26));
  if (coloured)
    annotations->AddActor2D(colour_bar(colours, spec.colour_label.empty() ? default_colour_label(spec.colouring) : spec.colour_label,
                                       cols * w, bar_w, W));
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  if (transparent) grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOff();
  grab->Update();
  require_visible(grab->GetOutput(), panels, transparent);
  if (!spec.camera_path.empty()) write_camera(camera, panels, W, H, spec.camera_path);
  const auto tmp = temporary_sibling(png_path);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(tmp)) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw OutputError(png_path + ": could not write the PNG");
  }
  commit_path(tmp, png_path);
}

}  // namespace fairshape::render
