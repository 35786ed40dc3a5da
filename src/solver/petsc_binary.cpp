#include "fairshape/solver/petsc_binary.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "fairshape/core/error.h"

namespace fairshape::petsc {
namespace {

constexpr std::int32_t kMatFileClassId = 1211216;  // PETSc's MAT_FILE_CLASSID
constexpr std::int32_t kVecFileClassId = 1211214;  // VEC_FILE_CLASSID

template <class T>
T big_endian(T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  std::memcpy(&v, b, sizeof(T));
  return v;
}
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "this writer swaps bytes for a little-endian machine");

class Writer {
 public:
  explicit Writer(const std::string& file) : file_(file), out_(file, std::ios::binary | std::ios::trunc) {
    if (!out_) throw OutputError(file + ": cannot be written");
  }
  template <class T>
  void put(T v) {
    v = big_endian(v);
    out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void close() {
    out_.close();
    if (!out_) throw OutputError(file_ + ": writing failed (disk full?)");
  }

 private:
  std::string file_;
  std::ofstream out_;
};

std::int32_t int32(Eigen::Index v, const std::string& file) {
  if (v > INT32_MAX) throw OutputError(file + ": more than 2^31 entries do not fit PETSc's 32-bit binary format");
  return static_cast<std::int32_t>(v);
}

}  // namespace

void write_matrix_file(const std::string& file, const SparseMatrix& A) {
  RowSparseMatrix R(A);
  R.makeCompressed();
  Writer w(file);
  w.put(kMatFileClassId);
  w.put(int32(R.rows(), file));
  w.put(int32(R.cols(), file));
  w.put(int32(R.nonZeros(), file));
  for (Eigen::Index i = 0; i < R.rows(); ++i) w.put(int32(R.outerIndexPtr()[i + 1] - R.outerIndexPtr()[i], file));
  for (Eigen::Index k = 0; k < R.nonZeros(); ++k) w.put(static_cast<std::int32_t>(R.innerIndexPtr()[k]));
  for (Eigen::Index k = 0; k < R.nonZeros(); ++k) w.put(R.valuePtr()[k]);
  w.close();
}

void write_vector_file(const std::string& file, const Eigen::VectorXd& v) {
  Writer w(file);
  w.put(kVecFileClassId);
  w.put(int32(v.size(), file));
  for (Eigen::Index i = 0; i < v.size(); ++i) w.put(v[i]);
  w.close();
}

Eigen::VectorXd read_vector_file(const std::string& file, Eigen::Index n) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IOError(file + ": cannot be read");
  const auto get = [&](auto& v) {
    in.read(reinterpret_cast<char*>(&v), sizeof(v));
    v = big_endian(v);
  };
  std::int32_t id = 0, size = 0;
  get(id);
  get(size);
  if (!in || id != kVecFileClassId || size != n)
    throw IOError(file + ": not a PETSc vector of " + std::to_string(n) + " entries");
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) get(v[i]);
  if (!in) throw IOError(file + ": ends early");
  return v;
}

}  // namespace fairshape::petsc
