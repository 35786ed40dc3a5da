// PETSc's binary matrix and vector files, written and read without PETSc: a process hands its
// system to a distributed MPI job (petsc_distributed.h) without becoming an MPI process itself.
// The format (PETSc's MatView/VecView to a binary viewer): big-endian 32-bit integers and IEEE
// doubles; a matrix is its class id, rows, columns, stored entries, each row's count, the column
// indices and the values, row by row; a vector is its class id, size and values.
#pragma once

#include <string>

#include "fairshape/core/types.h"

namespace fairshape::petsc {

//! \throw OutputError when the file cannot be written completely.
void write_matrix_file(const std::string& file, const SparseMatrix& A);
void write_vector_file(const std::string& file, const Eigen::VectorXd& v);
//! \throw IOError naming the file when it is not a PETSc vector file of `n` entries.
Eigen::VectorXd read_vector_file(const std::string& file, Eigen::Index n);

}  // namespace fairshape::petsc
