#include "fairshape/solver/matrix_fingerprint.h"

#include "fairshape/core/parallel_for.h"  // both back ends' solvers hash (serial without TBB)

#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

namespace fairshape {
namespace {

// Columns are hashed in fixed blocks and the block hashes combined in order, so the result does
// not depend on how many threads hashed the blocks.
constexpr Eigen::Index kColumnsPerBlock = 4096;
constexpr Eigen::Index kParallelEntries = Eigen::Index(1) << 16;

// xxHash64's primes and round. Four lanes take words in turn, so the pass is not one long chain
// of dependent multiplications: on 27M entries a single chain took 1.6 times a 3-column product
// with A, four lanes about one.
constexpr std::uint64_t kPrime1 = 0x9e3779b185ebca87ull, kPrime2 = 0xc2b2ae3d27d4eb4full,
                        kPrime3 = 0x165667b19e3779f9ull, kPrime4 = 0x85ebca77c2b2ae63ull;

inline std::uint64_t mix_in(std::uint64_t acc, std::uint64_t word) {
  return std::rotl(acc + word * kPrime2, 31) * kPrime1;
}

class Lanes {
 public:
  explicit Lanes(std::uint64_t seed) : lane_{seed + kPrime1 + kPrime2, seed + kPrime2, seed, seed - kPrime1} {}

  void add(std::uint64_t word) {
    lane_[next_] = mix_in(lane_[next_], word);
    next_ = (next_ + 1) & 3;
    ++words_;
  }
  //! n consecutive 8-byte words starting at `bytes` (any alignment).
  void add_words(const void* bytes, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(bytes);
    std::size_t i = 0;
    if (next_ == 0) {
      std::uint64_t a = lane_[0], b = lane_[1], c = lane_[2], d = lane_[3];
      for (; i + 4 <= n; i += 4) {
        a = mix_in(a, load(p + 8 * i));
        b = mix_in(b, load(p + 8 * i + 8));
        c = mix_in(c, load(p + 8 * i + 16));
        d = mix_in(d, load(p + 8 * i + 24));
      }
      lane_[0] = a, lane_[1] = b, lane_[2] = c, lane_[3] = d;
      words_ += i;
    }
    for (; i < n; ++i) add(load(p + 8 * i));
  }
  //! xxHash64's merge and avalanche: every bit of every lane reaches every bit of the result.
  std::uint64_t digest() const {
    std::uint64_t h = std::rotl(lane_[0], 1) + std::rotl(lane_[1], 7) + std::rotl(lane_[2], 12) + std::rotl(lane_[3], 18);
    for (std::uint64_t lane : lane_) h = (h ^ mix_in(0, lane)) * kPrime1 + kPrime4;
    h += words_;
    h ^= h >> 33;
    h *= kPrime2;
    h ^= h >> 29;
    h *= kPrime3;
    return h ^ (h >> 32);
  }

 private:
  static std::uint64_t load(const unsigned char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, sizeof w);
    return w;
  }
  std::uint64_t lane_[4];
  unsigned next_ = 0;
  std::uint64_t words_ = 0;
};

struct Hashes {
  std::uint64_t pattern, values;
};

// Columns [begin, end) of a compressed matrix: their entry counts and row indices (the
// pattern), and their values' bits.
Hashes hash_columns(const SparseMatrix& A, Eigen::Index begin, Eigen::Index end) {
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr() + outer[begin];
  const double* values = A.valuePtr() + outer[begin];
  const auto entries = static_cast<std::size_t>(outer[end] - outer[begin]);
  Lanes pattern(static_cast<std::uint64_t>(begin)), value_bits(static_cast<std::uint64_t>(begin));
  for (Eigen::Index j = begin; j < end; ++j) pattern.add(static_cast<std::uint64_t>(outer[j + 1] - outer[j]));
  static_assert(sizeof(*inner) == 4, "row indices are hashed two to a word");
  pattern.add_words(inner, entries / 2);
  if (entries % 2) pattern.add(static_cast<std::uint64_t>(inner[entries - 1]));
  value_bits.add_words(values, entries);
  return {pattern.digest(), value_bits.digest()};
}

}  // namespace

MatrixFingerprint::MatrixFingerprint(const SparseMatrix& A)
    : rows_(A.rows()), cols_(A.cols()), nonzeros_(A.nonZeros()) {
  if (!A.isCompressed()) {  // rare (solvers are handed compressed matrices): hash its compressed copy
    SparseMatrix compressed = A;
    compressed.makeCompressed();
    *this = MatrixFingerprint(compressed);
    return;
  }
  const Eigen::Index n = A.outerSize(), blocks = (n + kColumnsPerBlock - 1) / kColumnsPerBlock;
  std::vector<Hashes> per_block(static_cast<std::size_t>(blocks));
  const auto hash_blocks = [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index k = first; k < last; ++k)
      per_block[static_cast<std::size_t>(k)] =
          hash_columns(A, k * kColumnsPerBlock, std::min(n, (k + 1) * kColumnsPerBlock));
  };
  if (nonzeros_ >= kParallelEntries)
    for_each_range(Eigen::Index{0}, blocks, 1, [&](const IndexRange<Eigen::Index>& r) { hash_blocks(r.begin(), r.end()); });
  else
    hash_blocks(0, blocks);
  Lanes pattern(0), values(1);
  for (const Hashes& h : per_block) {
    pattern.add(h.pattern);
    values.add(h.values);
  }
  pattern_ = pattern.digest();
  values_ = values.digest();
}

}  // namespace fairshape
