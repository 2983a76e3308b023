#include "reduction/state_space.hpp"

#include <Eigen/Dense>
#include <stdexcept>

namespace rigflex::reduction {
namespace {

// The state-space matrices of xi'' + Z xi' + Lambda xi = F u, y = [G xi; G xi'].
StateSpace second_order_form(const Eigen::MatrixXd& Lambda, const Eigen::MatrixXd& Z, const Eigen::MatrixXd& F,
                             const Eigen::MatrixXd& G) {
  const Eigen::Index n = Lambda.rows();
  const Eigen::Index nb = F.cols();
  StateSpace s;
  s.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.A.topRightCorner(n, n).setIdentity();
  s.A.bottomLeftCorner(n, n) = -Lambda;
  s.A.bottomRightCorner(n, n) = -Z;
  s.B = Eigen::MatrixXd::Zero(2 * n, nb);
  s.B.bottomRows(n) = F;
  s.C = Eigen::MatrixXd::Zero(2 * nb, 2 * n);
  s.C.topLeftCorner(nb, n) = G;
  s.C.bottomRightCorner(nb, n) = G;
  s.D = Eigen::MatrixXd::Zero(2 * nb, nb);
  return s;
}

// T = [rigid made M-orthonormal, elastic modes in their M-orthogonal
// complement] and the elastic eigenvalues, for M = L L'.
struct ModalBasis {
  Eigen::MatrixXd T;
  Eigen::VectorXd elastic_eigenvalues;
};

ModalBasis modal_basis(const Eigen::MatrixXd& K, const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& rigid) {
  const Eigen::Index n = K.rows();
  const Eigen::Index r = rigid.cols();
  // In the coordinates w = L' z the mass is the identity; U spans the rigid motions there.
  const Eigen::MatrixXd U0 = llt.matrixU() * rigid;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(U0);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd diag = qr.matrixQR().diagonal().head(r).cwiseAbs();
  if (r > 0 && !(diag.minCoeff() > 1e-10 * diag.maxCoeff()))
    throw std::invalid_argument("state_space_form: the rigid motions are not independent");
  const Eigen::MatrixXd U = Q.leftCols(r);
  const Eigen::MatrixXd W = Q.rightCols(n - r);
  // S = L^-1 K L^-T, seen on the complement only: its coupling to U is K's
  // round-off on the rigid motions, which the projection drops.
  const Eigen::MatrixXd LinvW = llt.matrixU().solve(W);  // L^-T W
  Eigen::MatrixXd Se = LinvW.transpose() * K * LinvW;
  Se = 0.5 * (Se + Se.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Se);
  if (eig.info() != Eigen::Success) throw std::invalid_argument("state_space_form: elastic eigen decomposition failed");
  ModalBasis b;
  b.T.resize(n, n);
  b.T.leftCols(r) = llt.matrixU().solve(U);
  b.T.rightCols(n - r) = LinvW * eig.eigenvectors();
  b.elastic_eigenvalues = eig.eigenvalues();
  return b;
}

}  // namespace

StateSpace state_space_form(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                            Eigen::Index interface_dofs, const Eigen::MatrixXd& rigid) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n || C.rows() != n || C.cols() != n) {
    throw std::invalid_argument("state_space_form: K, M and C must be square and of equal size");
  }
  if (interface_dofs < 1 || interface_dofs > n) {
    throw std::invalid_argument("state_space_form: interface DOF count outside 1..n");
  }
  if (rigid.size() > 0 && (rigid.rows() != n || rigid.cols() > n)) {
    throw std::invalid_argument("state_space_form: the rigid motions must have as many rows as K");
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("state_space_form: the reduced mass matrix is not positive definite");
  }
  const Eigen::Index nb = interface_dofs;
  const Eigen::MatrixXd E = Eigen::MatrixXd::Identity(n, nb);
  if (rigid.size() == 0) {
    StateSpace s = second_order_form(llt.solve(K), llt.solve(C), llt.solve(E), E.transpose());
    s.T = Eigen::MatrixXd::Identity(n, n);
    s.coordinates = StateCoordinates::physical;
    return s;
  }
  const Eigen::Index r = rigid.cols();
  const ModalBasis b = modal_basis(K, llt, rigid);
  Eigen::MatrixXd Lambda = Eigen::MatrixXd::Zero(n, n);
  Lambda.diagonal().tail(n - r) = b.elastic_eigenvalues;
  Eigen::MatrixXd Z = b.T.transpose() * C * b.T;
  Z = 0.5 * (Z + Z.transpose());
  // C leaves the rigid motions undamped (rayleigh_damping_matrix); what is
  // left there is round-off.
  Z.topRows(r).setZero();
  Z.leftCols(r).setZero();
  StateSpace s = second_order_form(Lambda, Z, b.T.topRows(nb).transpose(), b.T.topRows(nb));
  s.T = b.T;
  s.coordinates = StateCoordinates::modal;
  s.rigid_body_modes = static_cast<int>(r);
  return s;
}

}  // namespace rigflex::reduction
