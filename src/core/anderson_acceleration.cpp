#include "primo/anderson_acceleration.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "primo/parallel.h"

namespace primo {
namespace {

constexpr int kEmbedding = 7;  // unit quaternion (4) and position (3)

// The quaternion's sign is chosen on the side of `align` (a previous embedding, or null), so
// that nearby rotations have nearby embeddings.
void embed(const BodyState& s, const double* align, double* out) {
  const Eigen::Quaterniond q(s.rotation);
  double sign = 1.0;
  const double side = align ? q.w() * align[0] + q.x() * align[1] + q.y() * align[2] +
                                  q.z() * align[3]
                            : q.w();
  if (side < 0.0) sign = -1.0;
  out[0] = sign * q.w();
  out[1] = sign * q.x();
  out[2] = sign * q.y();
  out[3] = sign * q.z();
  for (int k = 0; k < 3; ++k) out[4 + k] = s.position[k];
}

}  // namespace

void AndersonAcceleration::reset() {
  last_residual_.clear();
  last_image_.clear();
  delta_residual_.clear();
  delta_image_.clear();
  gram_.resize(0, 0);
}

std::vector<BodyState> AndersonAcceleration::propose(const std::vector<BodyState>& input,
                                                     const std::vector<BodyState>& image) {
  if (history_ <= 0) return image;
  const size_t n_bodies = image.size(), n = n_bodies * kEmbedding;
  // Image g = G(x) and residual f = G(x) - x, embedded.
  std::vector<double> g(n), f(n);
  parallel_chunks(n_bodies, kParallelGrain, [&](size_t begin, size_t end) {
    double x[kEmbedding];
    const bool aligned = last_image_.size() == n;
    for (size_t b = begin; b < end; ++b) {
      embed(image[b], aligned ? &last_image_[b * kEmbedding] : nullptr, &g[b * kEmbedding]);
      embed(input[b], &g[b * kEmbedding], x);
      for (int k = 0; k < kEmbedding; ++k) f[b * kEmbedding + k] = g[b * kEmbedding + k] - x[k];
    }
  });

  if (last_residual_.size() == n) {
    // The newest differences. The history is kept in single precision: it halves the memory
    // traffic that dominates a proposal on large meshes, and differences of nearby states lose
    // nothing that matters to a least-squares fit whose result is checked against the energy.
    // The last image stays in double, since its difference with the next one is small.
    if (int(delta_residual_.size()) == history_) {
      std::vector<float> reused_residual = std::move(delta_residual_.front());
      std::vector<float> reused_image = std::move(delta_image_.front());
      delta_residual_.erase(delta_residual_.begin());
      delta_image_.erase(delta_image_.begin());
      delta_residual_.push_back(std::move(reused_residual));
      delta_image_.push_back(std::move(reused_image));
      const int k = int(gram_.rows()) - 1;
      const Eigen::MatrixXd kept = gram_.bottomRightCorner(k, k);
      gram_ = kept;
    } else {
      delta_residual_.emplace_back();
      delta_image_.emplace_back();
    }
    std::vector<float>& dr = delta_residual_.back();
    std::vector<float>& dg = delta_image_.back();
    dr.resize(n);
    dg.resize(n);
    parallel_chunks(n, kParallelGrain * kEmbedding, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        dr[i] = float(f[i] - double(last_residual_[i]));
        dg[i] = float(g[i] - last_image_[i]);
      }
    });
  } else {
    reset();
  }
  const int m = int(delta_residual_.size());
  std::vector<BodyState> next = image;
  if (m > 0) {
    // One pass for the Gram matrix's new column (the others are kept from earlier calls) and
    // the right-hand side dF^T f of the least-squares problem min |f - dF theta|.
    const std::vector<float>& newest = delta_residual_.back();
    // Per chunk: m column entries, then m right-hand sides; chunks added in order.
    const size_t chunks = chunk_count(n, kParallelGrain * kEmbedding);
    std::vector<double> sums(chunks * 2 * size_t(m), 0.0);
    parallel_tasks(chunks, [&](size_t k) {
      const size_t begin = chunk_begin(n, chunks, k), end = chunk_begin(n, chunks, k + 1);
      double* s = &sums[k * 2 * size_t(m)];
      for (int a = 0; a < m; ++a) {
        const float* da = delta_residual_[a].data();
        double column = 0.0, rhs = 0.0;
        for (size_t i = begin; i < end; ++i) {
          column += double(da[i]) * double(newest[i]);
          rhs += double(da[i]) * f[i];
        }
        s[a] = column;
        s[m + a] = rhs;
      }
    });
    gram_.conservativeResize(m, m);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) {
      double column = 0.0, right = 0.0;
      for (size_t k = 0; k < chunks; ++k) {
        column += sums[k * 2 * size_t(m) + size_t(a)];
        right += sums[k * 2 * size_t(m) + size_t(m + a)];
      }
      gram_(a, m - 1) = gram_(m - 1, a) = column;
      rhs[a] = right;
    }
    // Lightly regularized: the columns become nearly dependent as the iteration converges.
    Eigen::MatrixXd regularized = gram_;
    regularized.diagonal().array() += 1e-10 * gram_.trace() / m + 1e-300;
    const Eigen::VectorXd theta = regularized.ldlt().solve(rhs);
    if (theta.allFinite()) {
      parallel_chunks(n_bodies, kParallelGrain, [&](size_t begin, size_t end) {
        double x[kEmbedding];
        for (size_t b = begin; b < end; ++b) {
          const size_t at = b * kEmbedding;
          for (int k = 0; k < kEmbedding; ++k) {
            x[k] = g[at + k];
            for (int a = 0; a < m; ++a) x[k] -= theta[a] * double(delta_image_[a][at + k]);
          }
          // Unchanged through the history: keep the image's rotation bit for bit.
          if (x[0] != g[at] || x[1] != g[at + 1] || x[2] != g[at + 2] || x[3] != g[at + 3]) {
            const Eigen::Quaterniond q(x[0], x[1], x[2], x[3]);
            const double norm = q.norm();
            if (norm > 0.0)
              next[b].rotation = Eigen::Quaterniond(q.coeffs() / norm).toRotationMatrix();
          }
          for (int k = 0; k < 3; ++k) next[b].position[k] = x[4 + k];
        }
      });
    }
  }
  last_residual_.assign(f.begin(), f.end());
  last_image_ = std::move(g);
  return next;
}

}  // namespace primo
