#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

namespace reference {
std::unique_ptr<Subdivider> make_mask_subdivider();
}
std::unique_ptr<Subdivider> make_parallel_subdivider();

std::unique_ptr<Subdivider> make_subdivider(Backend backend) {
  return backend == Backend::Reference ? reference::make_mask_subdivider() : make_parallel_subdivider();
}

}  // namespace fairshape
