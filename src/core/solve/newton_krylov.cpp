#include "primo/solve/newton_krylov.h"

#include <cmath>
#include <limits>
#include <utility>

#include "primo/util/parallel.h"
#include "primo/solve/rigid_hessian.h"
#include "rigid_blocks.h"

namespace primo {

struct NewtonKrylov::Impl {
  const RigidSystem& sys;
  NewtonKrylovOptions options;
  // The structure, built by the first step in three parts with `interrupt` asked between
  // them (at 240k faces it takes 0.25-0.3 s, and the editor's settle must give way to a new
  // drag within a fraction of that), or at once by build_structure.
  MultigridRows rows;  // the order until the Hessian takes it, the partition until the multigrid
  std::unique_ptr<RigidHessian> hessian_storage;
  std::unique_ptr<RigidMultigrid> multigrid_storage;
  BlockVector x, r, z, p, q;
  std::vector<Vec3> position;
  std::vector<BodyState> trial;  // the line search's, kept from step to step

  Impl(const RigidSystem& s, const NewtonKrylovOptions& o) : sys(s), options(o) {}

  // False when `interrupt` said so before the structure was complete (the parts built stay).
  bool build(const std::function<bool()>& interrupt) {
    auto interrupted = [&] { return interrupt && interrupt(); };
    if (!hessian_storage) {
      if (rows.order.empty()) {
        rows = multigrid_rows(sys);
        if (interrupted()) return false;
      }
      hessian_storage = std::make_unique<RigidHessian>(sys, std::move(rows.order));
      if (interrupted()) return false;
    }
    if (!multigrid_storage)
      // The steps' own vectors are made beside the multigrid (their first touch is page faults,
      // 65 MB at 240k faces), where a core is free: a solve from rest builds the structure
      // beside a coarse factorization that ends before it.
      parallel_tasks(2, [&](size_t task) {
        if (task == 0)
          multigrid_storage = std::make_unique<RigidMultigrid>(
              sys, hessian_storage->matrix().pairs, options.multigrid, hessian_storage->order(),
              std::move(rows.partition));
        else
          make_vectors();
      });
    return true;
  }

  void make_vectors() {
    const size_t n = size_t(sys.n_bodies());
    for (BlockVector* v : {&x, &r, &z, &p, &q}) parallel_assign(*v, n, Vec6::Zero().eval());
    parallel_assign(position, n, Vec3::Zero().eval());
    trial.resize(n);
  }
  RigidHessian& hessian() { return *hessian_storage; }
  RigidMultigrid& multigrid() { return *multigrid_storage; }

  // The root t >= 0 of |xw + t pw|^2 = bound^2 for |xw| <= bound and pw != 0 (the constant
  // term is <= 0): how far along pw the turn xw may go.
  static double turn_room(const Vec3& xw, const Vec3& pw, double bound) {
    const double a = pw.squaredNorm(), half_b = xw.dot(pw);
    const double c = std::min(0.0, xw.squaredNorm() - bound * bound);
    return (std::sqrt(half_b * half_b - a * c) - half_b) / a;
  }

  // q = H p, p . q, and the largest t for which no body's turn |x_w + t p_w| exceeds max_turn
  // (every |x_w| is within it already; infinity when none limits it) in one pass: the product
  // streams p and the rows anyway, where the dot product and the bound each read p and x
  // again. A minimum, the same whatever the chunks.
  struct Product {
    double curvature = 0.0;
    double room = std::numeric_limits<double>::infinity();
  };
  Product product_along(const BlockMatrix& h) {
    const size_t n = p.size();
    q.resize(n);
    const double bound = options.max_turn;
    return parallel_reduce(
        n, kParallelGrain / 4, Product{},
        [&](size_t begin, size_t end) {
          Product part;
          for (size_t b = begin; b < end; ++b) {
            q[b] = h.row_product(int(b), p);
            part.curvature += p[b].dot(q[b]);
            if (!(bound > 0.0)) continue;
            const Vec3 xw = x[b].tail<3>(), pw = p[b].tail<3>();
            if (pw.squaredNorm() > 0.0) part.room = std::min(part.room, turn_room(xw, pw, bound));
          }
          return part;
        },
        [](const Product& u, const Product& v) {
          return Product{u.curvature + v.curvature, std::min(u.room, v.room)};
        });
  }

  // r . z and z . q in one pass, each summed as dot() sums it.
  std::pair<double, double> dots_of_z() const {
    return parallel_reduce(
        z.size(), kParallelGrain, std::pair<double, double>{0.0, 0.0},
        [&](size_t begin, size_t end) {
          std::pair<double, double> sums{0.0, 0.0};
          for (size_t b = begin; b < end; ++b) {
            sums.first += double(r[b].dot(z[b]));
            sums.second += double(z[b].dot(q[b]));
          }
          return sums;
        },
        [](const auto& u, const auto& v) {
          return std::pair<double, double>{u.first + v.first, u.second + v.second};
        });
  }

  double largest_turn() const {
    return parallel_reduce(
        x.size(), kParallelGrain, 0.0,
        [&](size_t begin, size_t end) {
          double largest = 0.0;
          for (size_t b = begin; b < end; ++b) largest = std::max(largest, x[b].tail<3>().norm());
          return largest;
        },
        [](double a, double b) { return std::max(a, b); });
  }

  // Conjugate gradients on H x = -gradient from zero. Returns the iterations, -1 when the
  // first direction already has non-positive curvature (H is not positive definite there), or
  // kInterrupted. `bounded` tells whether they stopped on the largest turn.
  static constexpr int kInterrupted = -2;
  int conjugate_gradients(bool& bounded, NewtonKrylovStep& step,
                          const std::function<bool()>& interrupt) {
    bounded = false;
    step.model_decreases.clear();
    const BlockMatrix& h = hessian().matrix();
    const BlockVector& gradient = hessian().gradient();
    const size_t n = gradient.size();
    x.resize(n);
    r.resize(n);
    parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
      for (size_t b = begin; b < end; ++b) {
        x[b].setZero();
        r[b] = -gradient[b];
      }
    });
    multigrid().apply(r, z);
    ++step.preconditioner_applications;
    parallel_copy(z, p);
    double rz = dot(r, z);
    if (!(rz > 0.0)) return 0;
    double model_decrease = 0.0;
    int it = 0;
    while (it < options.max_cg_iterations) {
      if (interrupt && interrupt()) return kInterrupted;
      const Product product = product_along(h);
      const double curvature = product.curvature;
      if (!(curvature > 0.0)) return it == 0 ? -1 : it;  // keep what was found before it
      double alpha = rz / curvature;
      if (product.room < alpha) {  // the step would turn a body further than max_turn
        bounded = true;
        alpha = product.room;
      }
      parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
        for (size_t b = begin; b < end; ++b) {
          x[b] += alpha * p[b];
          r[b] -= alpha * q[b];
        }
      });
      ++it;
      if (bounded) break;
      // The model falls by alpha r.z / 2 along p (exact for conjugate directions; the
      // K-cycle's slight nonlinearity makes it an estimate), and the error left in the energy
      // norm is about the sum of the decreases still to come, which fall geometrically.
      const double decrease = 0.5 * alpha * rz;
      model_decrease += decrease;
      step.model_decreases.push_back(decrease);
      if (decrease <= options.stop_ratio * model_decrease) break;
      multigrid().apply(r, z);
      ++step.preconditioner_applications;
      const auto [rz_next, zq] = dots_of_z();
      if (!(rz_next > 0.0)) break;
      // Flexible (Polak-Ribiere) beta = z' . (r' - r) / (z . r), with r' - r = -alpha q: the
      // K-cycle is not quite a fixed linear map, and Fletcher-Reeves' rz'/rz assumes one.
      const double beta = -alpha * zq / rz;
      rz = rz_next;
      parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
        for (size_t b = begin; b < end; ++b) p[b] = z[b] + beta * p[b];
      });
    }
    return it;
  }
};

NewtonKrylov::NewtonKrylov(const RigidSystem& system, const NewtonKrylovOptions& options)
    : impl_(std::make_unique<Impl>(system, options)) {}
NewtonKrylov::~NewtonKrylov() = default;

void NewtonKrylov::build_structure() { impl_->build({}); }
bool NewtonKrylov::structure_built() const { return impl_->multigrid_storage != nullptr; }

NewtonKrylovStep NewtonKrylov::iterate(std::vector<BodyState>& state, double energy_before,
                                       const std::function<bool()>& interrupt) {
  Impl& m = *impl_;
  NewtonKrylovStep step;
  if ((interrupt && interrupt()) || !m.build(interrupt)) {
    step.interrupted = true;
    return step;
  }
  step.energy_before = std::isnan(energy_before) ? m.sys.energy(state) : energy_before;
  step.energy_after = step.energy_before;
  m.position.resize(state.size());
  const std::vector<int>& order = m.hessian().order();
  parallel_chunks(state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) m.position[r] = state[size_t(order[r])].position;
  });

  // The exact Hessian first; Gauss-Newton's when it or a block the preconditioner inverts is
  // not positive definite (assembled again then: keeping both would cost memory every step
  // for a fallback that is rare near a minimum).
  for (const bool exact : {true, false}) {
    m.hessian().assemble(state, exact);
    if (!m.multigrid().set_matrix(m.hessian().matrix(), m.position)) continue;
    bool bounded = false;
    const int iterations = m.conjugate_gradients(bounded, step, interrupt);
    if (iterations == Impl::kInterrupted) {
      step.interrupted = true;
      return step;
    }
    if (iterations <= 0) continue;
    step.largest_turn = m.largest_turn();
    step.turn_bounded = bounded;
    step.cg_iterations += iterations;
    const HalvedStep found =
        halve_until_lower(m.sys, state, step.energy_before, m.options.max_halvings, m.trial,
                          [&](double lambda, std::vector<BodyState>& out) {
                            m.hessian().move_into(state, m.x, lambda, out);
                          });
    if (found.lambda > 0.0) {
      step.energy_after = found.energy;
      step.step_scale = found.lambda;
      step.exact_hessian = exact;
      step.decreased = true;
      break;
    }
  }
  return step;
}

}  // namespace primo
