#include "primo/solve/anderson_acceleration.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "primo/util/error.h"
#include "primo/util/parallel.h"

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

void AndersonAcceleration::forget_history() {
  last_residual_.clear();
  for (auto* history : {&delta_residual_, &delta_image_}) {
    for (std::vector<float>& buffer : *history) spare_.push_back(std::move(buffer));
    history->clear();
  }
  gram_.resize(0, 0);
}

std::vector<float> AndersonAcceleration::spare_buffer() {
  if (spare_.empty()) return {};
  std::vector<float> buffer = std::move(spare_.back());
  spare_.pop_back();
  return buffer;
}

void AndersonAcceleration::reset() {
  forget_history();
  last_image_.clear();
  kept_ = Kept::None;
}

void AndersonAcceleration::refuse() {
  forget_history();
  if (kept_ == Kept::Proposal) kept_ = Kept::Image;
}

std::vector<BodyState> AndersonAcceleration::propose(const std::vector<BodyState>& input,
                                                     const std::vector<BodyState>& image) {
  std::vector<BodyState> next = image;
  propose(&input, image, next);
  return next;
}

bool AndersonAcceleration::propose(const std::vector<BodyState>* input,
                                   const std::vector<BodyState>& image,
                                   std::vector<BodyState>& next) {
  if (history_ <= 0) return false;
  const size_t n_bodies = image.size(), n = n_bodies * kEmbedding;
  const bool aligned = last_image_.size() == n;
  if (!input && (kept_ == Kept::None || !aligned ||
                 (kept_ == Kept::Proposal && proposal_embedding_.size() != n)))
    throw Error("Anderson acceleration: the last state is not known");
  // The input's embedding: the last image or proposal when the caller kept it (last_image_
  // is the last call's image until it is replaced below).
  const std::vector<double>* kept = input                     ? nullptr
                                    : kept_ == Kept::Proposal ? &proposal_embedding_
                                                              : &last_image_;
  const bool continues = last_residual_.size() == n;
  float* dr = nullptr;
  float* dg = nullptr;
  if (continues) {
    // The newest differences. The history is kept in single precision: it halves the memory
    // traffic that dominates a proposal on large meshes, and differences of nearby states lose
    // nothing that matters to a least-squares fit whose result is checked against the energy.
    // The last image stays in double, since its difference with the next one is small.
    if (int(delta_residual_.size()) == history_) {
      std::rotate(delta_residual_.begin(), delta_residual_.begin() + 1, delta_residual_.end());
      std::rotate(delta_image_.begin(), delta_image_.begin() + 1, delta_image_.end());
      const int k = int(gram_.rows()) - 1;
      const Eigen::MatrixXd kept_gram = gram_.bottomRightCorner(k, k);
      gram_ = kept_gram;
    } else {
      delta_residual_.push_back(spare_buffer());
      delta_image_.push_back(spare_buffer());
    }
    delta_residual_.back().resize(n);
    delta_image_.back().resize(n);
    dr = delta_residual_.back().data();
    dg = delta_image_.back().data();
  } else {
    forget_history();
  }
  // One pass: the image g = G(x) and the residual f = G(x) - x, embedded, their differences
  // with the last ones, and g and f kept for the next call (last_image_ is overwritten in
  // place, after its entries were read).
  std::vector<double>& f = residual_;
  f.resize(n);
  last_residual_.resize(n);
  last_image_.resize(n);
  parallel_chunks(n_bodies, kParallelGrain, [&](size_t begin, size_t end) {
    double x[kEmbedding], g[kEmbedding];
    for (size_t b = begin; b < end; ++b) {
      const size_t at = b * kEmbedding;
      double* last = &last_image_[at];
      embed(image[b], aligned ? last : nullptr, g);
      if (kept) {
        const double* k = &(*kept)[at];
        const double side = k[0] * g[0] + k[1] * g[1] + k[2] * g[2] + k[3] * g[3];
        const double sign = side < 0.0 ? -1.0 : 1.0;
        for (int i = 0; i < 4; ++i) x[i] = sign * k[i];
        for (int i = 4; i < kEmbedding; ++i) x[i] = k[i];
      } else {
        embed((*input)[b], g, x);
      }
      for (int k = 0; k < kEmbedding; ++k) {
        const double residual = g[k] - x[k];
        if (continues) {
          dr[at + k] = float(residual - double(last_residual_[at + k]));
          dg[at + k] = float(g[k] - last[k]);
        }
        f[at + k] = residual;
        last_residual_[at + k] = float(residual);
        last[k] = g[k];
      }
    }
  });
  const int m = int(delta_residual_.size());
  bool proposed = false;
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
      proposed = true;
      next.resize(n_bodies);
      proposal_embedding_.resize(n);
      parallel_chunks(n_bodies, kParallelGrain, [&](size_t begin, size_t end) {
        for (size_t b = begin; b < end; ++b) {
          const size_t at = b * kEmbedding;
          double* x = &proposal_embedding_[at];
          for (int k = 0; k < kEmbedding; ++k) {
            x[k] = last_image_[at + k];
            for (int a = 0; a < m; ++a) x[k] -= theta[a] * double(delta_image_[a][at + k]);
          }
          // Unchanged through the history: keep the image's rotation bit for bit.
          next[b].rotation = image[b].rotation;
          const double* g = &last_image_[at];
          if (x[0] != g[0] || x[1] != g[1] || x[2] != g[2] || x[3] != g[3]) {
            const double norm = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]);
            if (norm > 0.0) {
              for (int k = 0; k < 4; ++k) x[k] /= norm;
              next[b].rotation = Eigen::Quaterniond(x[0], x[1], x[2], x[3]).toRotationMatrix();
            } else {
              for (int k = 0; k < 4; ++k) x[k] = g[k];  // the image's rotation is kept
            }
          }
          for (int k = 0; k < 3; ++k) next[b].position[k] = x[4 + k];
        }
      });
    }
  }
  kept_ = proposed ? Kept::Proposal : Kept::Image;
  return proposed;
}

}  // namespace primo
