// For helpers both back ends share that run over an index range in parallel only for speed:
// with TBB, for_each_range is tbb::parallel_for over a tbb::blocked_range; in a build without
// TBB (FAIRSHAPE_WITH_TBB=0) it calls the body once on the whole range, serially. Bodies that
// write disjoint outputs give the same results either way.
#pragma once

#include <cstddef>

#include "fairshape/core/backend.h"

#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

namespace fairshape {

#if FAIRSHAPE_WITH_TBB
template <class Index>
using IndexRange = tbb::blocked_range<Index>;
#else
template <class Index>
class IndexRange {
 public:
  IndexRange(Index begin, Index end) : begin_(begin), end_(end) {}
  Index begin() const { return begin_; }
  Index end() const { return end_; }

 private:
  Index begin_, end_;
};
#endif

template <class Index, class Body>
void for_each_range(Index begin, Index end, [[maybe_unused]] std::size_t grain, const Body& body) {
#if FAIRSHAPE_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<Index>(begin, end, grain), body);
#else
  body(IndexRange<Index>(begin, end));
#endif
}

}  // namespace fairshape
