// PETSc inside fairshape (the petsc_* solvers): initialised once, on first use, and finalised at
// exit. A process started by `fairshape run` is not an MPI job: PETSc then runs as a singleton
// MPI process (one rank); distributed solves run as a separate MPI job (petsc_distributed.h).
// Every PETSc call goes through FS_PETSC, which turns an error code into a SolverError carrying
// PETSc's own message: PETSc prints nothing to stderr and never aborts the process.
#pragma once

#include <petscksp.h>

#include <string>
#include <utility>

#include "fairshape/core/types.h"

namespace fairshape::petsc {

//! PetscInitialize once per process (MPI_Init with it, unless MPI is up already). `argc/argv`
//! only for a program that is itself an MPI job (the distributed worker).
void initialize(int* argc = nullptr, char*** argv = nullptr);
//! \throw SolverError naming `what` and PETSc's message when `code` is an error.
void check(PetscErrorCode code, const char* what);
#define FS_PETSC(call) ::fairshape::petsc::check((call), #call)

//! Owns one PETSc object (Mat, Vec, KSP, …) and destroys it with `Destroy`.
template <class T, PetscErrorCode (*Destroy)(T*)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(T object) : object_(object) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : object_(std::exchange(o.object_, nullptr)) {}
  Handle& operator=(Handle&& o) noexcept {
    reset();
    object_ = std::exchange(o.object_, nullptr);
    return *this;
  }
  ~Handle() { reset(); }
  void reset() {
    if (object_) Destroy(&object_);  // errors on destruction have nowhere to go
    object_ = nullptr;
  }
  T get() const { return object_; }
  T* out() {  // for PETSc's creation functions
    reset();
    return &object_;
  }
  explicit operator bool() const { return object_ != nullptr; }

 private:
  T object_ = nullptr;
};
using MatHandle = Handle<Mat, MatDestroy>;
using VecHandle = Handle<Vec, VecDestroy>;
using KspHandle = Handle<KSP, KSPDestroy>;
using ViewerHandle = Handle<PetscViewer, PetscViewerDestroy>;

//! A one-rank AIJ copy of A (every stored entry: fairshape's systems store both triangles).
MatHandle to_petsc(const SparseMatrix& A);
//! A one-rank copy of column `c` of x.
VecHandle to_petsc(const Eigen::MatrixXd& x, Eigen::Index c);
//! Copies v (one rank) into column `c` of x.
void copy_to_column(Vec v, Eigen::MatrixXd& x, Eigen::Index c);

//! PETSc's binary files (petsc_binary.h writes them without PETSc), read by every rank of `comm`:
//! MatLoad and VecLoad share the rows out in PETSc's default layout, the same for a matrix's rows,
//! a prolongation's columns and a vector of that size.
MatHandle read_matrix(MPI_Comm comm, const std::string& file);
VecHandle read_vector(MPI_Comm comm, const std::string& file);
//! Written from every rank of v's communicator (VecView gathers to rank 0).
void write_vector(const std::string& file, Vec v);

}  // namespace fairshape::petsc
