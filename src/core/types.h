// Eigen aliases used at every module boundary.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace fairshape {

using Vec3 = Eigen::Vector3d;
using MatrixX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;  // #V by 3 positions
using SparseMatrix = Eigen::SparseMatrix<double>;                            // column-major
using RowSparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Triplet = Eigen::Triplet<double>;
using Triplets = std::vector<Triplet>;

}  // namespace fairshape
