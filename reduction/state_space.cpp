#include "reduction/state_space.hpp"

#include <Eigen/Dense>
#include <stdexcept>

namespace rigflex::reduction {

StateSpace state_space_form(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                            Eigen::Index interface_dofs) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n || C.rows() != n || C.cols() != n) {
    throw std::invalid_argument("state_space_form: K, M and C must be square and of equal size");
  }
  if (interface_dofs < 1 || interface_dofs > n) {
    throw std::invalid_argument("state_space_form: interface DOF count outside 1..n");
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("state_space_form: the reduced mass matrix is not positive definite");
  }
  const Eigen::Index nb = interface_dofs;
  StateSpace s;
  s.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.A.topRightCorner(n, n).setIdentity();
  s.A.bottomLeftCorner(n, n) = -llt.solve(K);
  s.A.bottomRightCorner(n, n) = -llt.solve(C);
  const Eigen::MatrixXd E = Eigen::MatrixXd::Identity(n, nb);
  s.B = Eigen::MatrixXd::Zero(2 * n, nb);
  s.B.bottomRows(n) = llt.solve(E);
  s.C = Eigen::MatrixXd::Zero(2 * nb, 2 * n);
  s.C.topLeftCorner(nb, nb).setIdentity();
  s.C.block(nb, n, nb, nb).setIdentity();
  s.D = Eigen::MatrixXd::Zero(2 * nb, nb);
  return s;
}

}  // namespace rigflex::reduction
