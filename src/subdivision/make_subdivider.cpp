#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

namespace reference {
std::unique_ptr<Subdivider> make_mask_subdivider();
}
std::unique_ptr<Subdivider> make_parallel_subdivider();

std::unique_ptr<Subdivider> make_subdivider(Backend backend) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? reference::make_mask_subdivider() : make_parallel_subdivider();
#else
  return reference::make_mask_subdivider();
#endif
}

}  // namespace fairshape
