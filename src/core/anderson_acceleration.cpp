#include "primo/anderson_acceleration.h"

#include <Eigen/Cholesky>

#include "primo/horn.h"

namespace primo {
namespace {

constexpr int kEmbedding = 12;  // rotation (9) and position (3)

std::vector<double> embed(const std::vector<BodyState>& state) {
  std::vector<double> v(state.size() * kEmbedding);
  for (size_t b = 0; b < state.size(); ++b) {
    double* out = &v[b * kEmbedding];
    for (int k = 0; k < 9; ++k) out[k] = state[b].rotation(k % 3, k / 3);
    for (int k = 0; k < 3; ++k) out[9 + k] = state[b].position[k];
  }
  return v;
}

}  // namespace

void AndersonAcceleration::reset() {
  last_residual_.clear();
  last_image_.clear();
  delta_residual_.clear();
  delta_image_.clear();
}

std::vector<BodyState> AndersonAcceleration::propose(const std::vector<BodyState>& input,
                                                     const std::vector<BodyState>& image) {
  if (history_ <= 0) return image;
  std::vector<double> g = embed(image);
  std::vector<double> f = embed(input);
  for (size_t i = 0; i < f.size(); ++i) f[i] = g[i] - f[i];

  if (!last_residual_.empty() && last_residual_.size() == f.size()) {
    // The last residual and image become the newest differences (in place: memory is
    // 2 x (history + 1) state vectors).
    for (size_t i = 0; i < f.size(); ++i) {
      last_residual_[i] = f[i] - last_residual_[i];
      last_image_[i] = g[i] - last_image_[i];
    }
    if (int(delta_residual_.size()) == history_) {
      delta_residual_.erase(delta_residual_.begin());
      delta_image_.erase(delta_image_.begin());
    }
    delta_residual_.push_back(std::move(last_residual_));
    delta_image_.push_back(std::move(last_image_));
  } else {
    reset();
  }
  const int m = int(delta_residual_.size());
  std::vector<BodyState> next = image;
  if (m > 0) {
    // Least squares min |f - dF theta| by the normal equations, lightly regularized (the
    // columns become nearly dependent as the iteration converges).
    Eigen::MatrixXd gram(m, m);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) {
      const std::vector<double>& da = delta_residual_[a];
      double r = 0.0;
      for (size_t i = 0; i < f.size(); ++i) r += da[i] * f[i];
      rhs[a] = r;
      for (int b = 0; b <= a; ++b) {
        const std::vector<double>& db = delta_residual_[b];
        double s = 0.0;
        for (size_t i = 0; i < f.size(); ++i) s += da[i] * db[i];
        gram(a, b) = gram(b, a) = s;
      }
    }
    gram.diagonal().array() += 1e-10 * gram.trace() / m + 1e-300;
    const Eigen::VectorXd theta = gram.ldlt().solve(rhs);
    if (theta.allFinite()) {
      double x[kEmbedding];
      for (size_t b = 0; b < next.size(); ++b) {
        const size_t at = b * kEmbedding;
        for (int k = 0; k < kEmbedding; ++k) {
          x[k] = g[at + k];
          for (int a = 0; a < m; ++a) x[k] -= theta[a] * delta_image_[a][at + k];
        }
        Mat3 r;
        for (int k = 0; k < 9; ++k) r(k % 3, k / 3) = x[k];
        // Unchanged through the history: keep the image's rotation bit for bit.
        if (r != image[b].rotation) next[b].rotation = horn_rotation(r.transpose(), image[b].rotation);
        for (int k = 0; k < 3; ++k) next[b].position[k] = x[9 + k];
      }
    }
  }
  last_residual_ = std::move(f);
  last_image_ = std::move(g);
  return next;
}

}  // namespace primo
