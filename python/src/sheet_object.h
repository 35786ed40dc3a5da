// fairshape.Sheet's C++ half: a variational sheet with its shape, shared by the sheet bindings
// (sheets.cpp: design_sheet; sheet_session.cpp: SheetSession hands out its sheets as copies).
#pragma once

#include <sstream>
#include <string>

#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/core/error.h"

namespace fairshape::python {

struct Sheet {
  bspline::SheetShape shape;
  bspline::VariationalSheet sheet;

  Eigen::Vector2d size() const { return {shape.spans_u * shape.span_size.x(), shape.spans_v * shape.span_size.y()}; }
  // Design units to base-span units, checked against the domain.
  Eigen::Vector2d spans(double u, double v, const std::string& what) const {
    const Eigen::Vector2d s = Eigen::Vector2d(u, v).cwiseQuotient(shape.span_size);
    if (!sheet.surface().in_domain(s.x(), s.y())) {
      std::ostringstream m;
      m << what << ": (u, v) = (" << u << ", " << v << ") is outside the sheet's domain [0, " << size().x() << "] x [0, "
        << size().y() << "] (design units: the sheet's size)";
      throw InvalidInput(m.str());
    }
    return s;
  }
};

}  // namespace fairshape::python
