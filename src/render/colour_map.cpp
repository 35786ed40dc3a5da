#include "fairshape/render/colour_map.h"

#include <array>

namespace fairshape::render {

const NameTable<ColourMap>& colour_map_names() {
  static const NameTable<ColourMap> t{{ColourMap::Viridis, "viridis"}, {ColourMap::Diverging, "diverging"},
                                      {ColourMap::Grey, "grey"}};
  return t;
}

vtkSmartPointer<vtkColorTransferFunction> colour_transfer(ColourMap map, double lo, double hi) {
  auto f = vtkSmartPointer<vtkColorTransferFunction>::New();
  switch (map) {
    case ColourMap::Viridis: {
      // Ten evenly spaced samples of viridis, interpolated in CIELAB: close to the full table
      // (the map is nearly linear in lightness by design).
      static const std::array<std::array<int, 3>, 10> samples{{{0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3e, 0x4a, 0x89},
                                                               {0x31, 0x68, 0x8e}, {0x26, 0x82, 0x8e}, {0x1f, 0x9e, 0x89},
                                                               {0x35, 0xb7, 0x79}, {0x6d, 0xcd, 0x59}, {0xb4, 0xde, 0x2c},
                                                               {0xfd, 0xe7, 0x25}}};
      f->SetColorSpaceToLab();
      for (std::size_t k = 0; k < samples.size(); ++k)
        f->AddRGBPoint(lo + (hi - lo) * static_cast<double>(k) / (samples.size() - 1), samples[k][0] / 255.0,
                       samples[k][1] / 255.0, samples[k][2] / 255.0);
      break;
    }
    case ColourMap::Diverging:
      // Moreland's diverging scheme (VTK's "diverging" colour space) between cool blue and warm red.
      f->SetColorSpaceToDiverging();
      f->AddRGBPoint(lo, 0.230, 0.299, 0.754);
      f->AddRGBPoint(hi, 0.706, 0.016, 0.150);
      break;
    case ColourMap::Grey:
      f->AddRGBPoint(lo, 0.15, 0.15, 0.15);
      f->AddRGBPoint(hi, 0.95, 0.95, 0.95);
      break;
  }
  f->Build();
  return f;
}

}  // namespace fairshape::render
