#include "fairshape/solver/petsc_runtime.h"

#include <cstdlib>
#include <mutex>

#include "fairshape/core/error.h"

namespace fairshape::petsc {
namespace {

void finalize_at_exit() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (!finalized) PetscFinalize();
}

}  // namespace

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("PETSc: ") + what + " failed: " + (text ? text : "error " + std::to_string(code)));
}

void initialize(int* argc, char*** argv) {
  static std::once_flag once;
  std::call_once(once, [&] {
    PetscBool up = PETSC_FALSE;
    PetscInitialized(&up);
    if (up) return;
    // fairshape's supervisor watches its workers' signals itself (a crashed run is recorded):
    // PETSc's handler would turn a segmentation fault into an MPI abort.
    check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
    check(PetscInitialize(argc, argv, nullptr, nullptr), "PetscInitialize");
    check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
    std::atexit(finalize_at_exit);
  });
}

MatHandle to_petsc(const SparseMatrix& A) {
  initialize();
  RowSparseMatrix R(A);
  R.makeCompressed();
  MatHandle M;
  FS_PETSC(MatCreate(PETSC_COMM_SELF, M.out()));
  FS_PETSC(MatSetSizes(M.get(), R.rows(), R.cols(), R.rows(), R.cols()));
  FS_PETSC(MatSetType(M.get(), MATSEQAIJ));
  // PetscInt is Eigen's StorageIndex (int) in Debian's 32-bit-index build: the CSR arrays pass as they are.
  static_assert(sizeof(PetscInt) == sizeof(RowSparseMatrix::StorageIndex), "PETSc built with 64-bit indices");
  FS_PETSC(MatSeqAIJSetPreallocationCSR(M.get(), reinterpret_cast<const PetscInt*>(R.outerIndexPtr()),
                                        reinterpret_cast<const PetscInt*>(R.innerIndexPtr()), R.valuePtr()));
  return M;
}

VecHandle to_petsc(const Eigen::MatrixXd& x, Eigen::Index c) {
  initialize();
  VecHandle v;
  FS_PETSC(VecCreateSeq(PETSC_COMM_SELF, x.rows(), v.out()));
  PetscScalar* data = nullptr;
  FS_PETSC(VecGetArray(v.get(), &data));
  for (Eigen::Index i = 0; i < x.rows(); ++i) data[i] = x(i, c);
  FS_PETSC(VecRestoreArray(v.get(), &data));
  return v;
}

void copy_to_column(Vec v, Eigen::MatrixXd& x, Eigen::Index c) {
  const PetscScalar* data = nullptr;
  FS_PETSC(VecGetArrayRead(v, &data));
  for (Eigen::Index i = 0; i < x.rows(); ++i) x(i, c) = data[i];
  FS_PETSC(VecRestoreArrayRead(v, &data));
}

namespace {
ViewerHandle open_binary(MPI_Comm comm, const std::string& file, PetscFileMode mode) {
  ViewerHandle viewer;
  FS_PETSC(PetscViewerBinaryOpen(comm, file.c_str(), mode, viewer.out()));
  // No .info side file: the manifest says what each file is.
  FS_PETSC(PetscViewerBinarySetSkipInfo(viewer.get(), PETSC_TRUE));
  return viewer;
}
}  // namespace

void write_vector(const std::string& file, Vec v) {
  ViewerHandle viewer = open_binary(PetscObjectComm(reinterpret_cast<PetscObject>(v)), file, FILE_MODE_WRITE);
  FS_PETSC(VecView(v, viewer.get()));
}

MatHandle read_matrix(MPI_Comm comm, const std::string& file) {
  ViewerHandle viewer = open_binary(comm, file, FILE_MODE_READ);
  MatHandle M;
  FS_PETSC(MatCreate(comm, M.out()));
  FS_PETSC(MatSetType(M.get(), MATAIJ));
  FS_PETSC(MatLoad(M.get(), viewer.get()));
  return M;
}

VecHandle read_vector(MPI_Comm comm, const std::string& file) {
  ViewerHandle viewer = open_binary(comm, file, FILE_MODE_READ);
  VecHandle v;
  FS_PETSC(VecCreate(comm, v.out()));
  FS_PETSC(VecLoad(v.get(), viewer.get()));
  return v;
}

}  // namespace fairshape::petsc
