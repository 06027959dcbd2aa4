#include "systems/anderson_mixing.h"

#include <Eigen/QR>

namespace fibra {

void AndersonMixer::reset() {
  g_.clear();
  f_.clear();
  used_ = 0;
}

Eigen::VectorXd AndersonMixer::next(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  const Split s = split(x, g);
  return s.xBar + s.fBar;
}

AndersonMixer::Split AndersonMixer::split(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  if (!g_.empty() && g_.back().size() != g.size()) reset();
  g_.push_back(g);
  f_.push_back(g - x);
  while (int(g_.size()) > memory_ + 1) {
    g_.pop_front();
    f_.pop_front();
  }
  const int p = int(g_.size()) - 1;
  used_ = 0;
  if (p == 0) return {x, g - x};
  Eigen::MatrixXd dF(g.size(), p), dG(g.size(), p);
  for (int i = 0; i < p; ++i) {
    dF.col(i) = f_[i + 1] - f_[i];
    dG.col(i) = g_[i + 1] - g_[i];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(dF);
  qr.setThreshold(1e-12);
  if (qr.rank() == 0) return {x, g - x};
  const Eigen::VectorXd gamma = qr.solve(f_.back());
  if (!gamma.allFinite()) return {x, g - x};
  used_ = int(qr.rank());
  return {x - (dG - dF) * gamma, f_.back() - dF * gamma};
}

}  // namespace fibra
