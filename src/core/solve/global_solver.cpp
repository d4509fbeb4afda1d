#include "primo/solve/global_solver.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <system_error>
#include <thread>
#include <tuple>

#include "primo/solve/block_matrix.h"
#include "primo/solve/horn.h"
#include "primo/util/parallel.h"
#include "rigid_blocks.h"

namespace primo {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// OpenBLAS limited to the calling thread for a scope, when `active` (and the BLAS in use is
// OpenBLAS; other BLAS libraries are left alone). Its helper threads spin for a while after every call, which
// on two cores takes them from our own threaded sweeps. Scopes may overlap on several threads
// (a background factorization and a solve): the first one in sets one thread, the last one out
// restores the setting.
class ScopedSingleThreadBlas {
 public:
  explicit ScopedSingleThreadBlas(bool active) : active_(active) {
    if (!active_) return;
    std::lock_guard<std::mutex> lock(mutex());
    if (holders()++ == 0 && get() && set()) {
      previous() = get()();
      if (previous() != 1) set()(1);
    }
  }
  ~ScopedSingleThreadBlas() {
    if (!active_) return;
    std::lock_guard<std::mutex> lock(mutex());
    if (--holders() == 0 && set() && previous() != 1) set()(previous());
  }
  ScopedSingleThreadBlas(const ScopedSingleThreadBlas&) = delete;
  ScopedSingleThreadBlas& operator=(const ScopedSingleThreadBlas&) = delete;

 private:
  using Get = int (*)();
  using Set = void (*)(int);
  static Get get() {
    static const auto f = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    return f;
  }
  static Set set() {
    static const auto f = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    return f;
  }
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static int& holders() {
    static int n = 0;
    return n;
  }
  static int& previous() {
    static int n = 1;
    return n;
  }
  bool active_;
};

}  // namespace

Mat3 rotation_from_vector(const Vec3& w) {
  const double theta = w.norm();
  const Mat3 k = cross_matrix(w);
  if (theta < 1e-8) return Mat3::Identity() + k + 0.5 * k * k;
  const double a = std::sin(theta) / theta;
  const double b = (1.0 - std::cos(theta)) / (theta * theta);
  return Mat3::Identity() + a * k + b * k * k;
}

struct GlobalSolver::Impl {
  const RigidSystem& sys;
  Factorization factorization;
  std::vector<std::array<int, 6>> dof;  // global index of each local dof, -1 when inactive
  std::vector<bool> active;
  int n = 0;

  // Off-diagonal blocks: one per coupled pair of active bodies, stored as (higher body,
  // lower body) so they land in the lower triangle.
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> coupling_pair;  // -1 when one side is inactive

  std::vector<Mat6> diag, off;
  std::vector<Mat3> second;
  std::vector<Vec6> grad;
  std::vector<std::vector<Vec6>> chunk_grad;  // assemble_gradient's chunks after the first

  SparseMatrix matrix;
  std::vector<std::array<int, 36>> diag_slots, off_slots;
  // Levenberg-Marquardt damping of exact-Hessian steps, relative to the system's scale, kept
  // across iterations: raised while the Hessian is indefinite, lowered after full steps.
  double exact_damping = 0.0;
  // The numeric factor held by the CHOLMOD objects, if any, and whether it has the
  // second-order terms (its steps then go through the exponential map).
  bool has_factor = false;
  bool factor_exact = false;
  GlobalSolverTimings timings;
  using SupernodalLLT = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
  std::unique_ptr<SupernodalLLT> supernodal = std::make_unique<SupernodalLLT>();
  Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower> simplicial;

  int max_reuse = std::numeric_limits<int>::max();  // steps a factor serves after its first
  int reused_step_halvings = GlobalSolver::kReusedStepHalvings;
  // Refactorization on a background thread (supernodal only): once the factor in use has
  // served its steps, the current matrix is factorized into `spare` while steps go on with
  // the old factor; the new factor takes over `lag` steps later, waiting for the thread if
  // needed. The handover happens at a fixed step, so results do not depend on timing.
  struct Background {
    int lag = 0;  // 0: off
    std::unique_ptr<SupernodalLLT> spare;
    bool spare_analyzed = false;
    SparseMatrix matrix;  // what the thread factorizes (the pattern of `matrix`)
    std::thread thread;
    bool running = false;
    int ready_at = 0;  // step count at which the new factor takes over
    bool exact = false;
    bool exact_failed = false;  // the last exact-Hessian factor was not positive definite
    // A Gauss-Newton factor failed too: the next refresh is made in the foreground, which
    // raises the damping until it succeeds.
    bool foreground_next = false;
    std::vector<Mat3> frames;  // the frames when its matrix was assembled
    bool ok = false;         // written by the thread, read after join
    double seconds = 0.0;    // written by the thread, read after join
  } background;
  double factorization_flops = 0.0;  // of the last supernodal factorization (CHOLMOD's count)
  // Co-rotated reuse: the caller's per-body frames now, and as they were when the matrix of
  // the factor in use was assembled. A reused factor is applied in the bodies' turned frames.
  const std::vector<Mat3>* frames = nullptr;
  std::vector<Mat3> factor_frames;
  int steps = 0;            // iterations so far
  int steps_on_factor = 0;  // steps taken with the factor in use (its first one included)

  Impl(const RigidSystem& s, Factorization f) : sys(s), factorization(f) {}
  bool supernodal_kind() const {
    return factorization == Factorization::Supernodal ||
           factorization == Factorization::SupernodalOneThread;
  }
  bool one_blas_thread() const { return factorization == Factorization::SupernodalOneThread; }
  ~Impl() {
    if (background.thread.joinable()) background.thread.join();
  }

  void build_pattern();
  void assemble(const std::vector<BodyState>& state);
  void assemble_gradient(const std::vector<BodyState>& state);  // grad only
  // The system matrix in `target` (the pattern of `matrix`), with the second-order rotation
  // terms if asked and Levenberg-Marquardt damping in the bodies' metrics.
  void fill(SparseMatrix& target, double damping, bool with_second_order,
            const std::vector<BodyState>& state) const;
  // Tiny damping for rank-deficient systems, and the scale of exact-Hessian damping.
  std::pair<double, double> damping_and_scale() const;
  bool factorize(double damping, bool with_second_order, const std::vector<BodyState>& state);
  // A Gauss-Newton factor, the damping raised while CHOLMOD finds the matrix not positive
  // definite (a few times at most).
  bool factorize_gauss_newton(double damping, const std::vector<BodyState>& state);
  void start_background(const std::vector<BodyState>& state, bool exact);  // after assemble()
  void finish_background();  // waits for the thread; its factor takes over if it succeeded
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs);
  Eigen::VectorXd solve_corotated(const Eigen::VectorXd& rhs);  // with a reused factor
  std::vector<BodyState> apply(const std::vector<BodyState>& state, const Eigen::VectorXd& delta,
                               double lambda, bool exponential) const;
};

void GlobalSolver::Impl::build_pattern() {
  const int nb = sys.n_bodies();
  dof.assign(nb, {-1, -1, -1, -1, -1, -1});
  active.assign(nb, false);
  for (int b = 0; b < nb; ++b) {
    const int mask = active_mask(sys.bodies[b].kind);
    for (int k = 0; k < 6; ++k)
      if (mask & (1 << k)) dof[b][k] = n++;
    active[b] = mask != 0;
  }

  PairNumbering numbering = number_pairs(moving_coupling_edges(sys));
  pairs = std::move(numbering.pairs);
  coupling_pair = std::move(numbering.pair_of);

  std::vector<Eigen::Triplet<double>> triplets;
  auto add_block = [&](int rb, int cb) {
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        const int gr = dof[rb][r], gc = dof[cb][c];
        if (gr >= 0 && gc >= 0 && gr >= gc) triplets.emplace_back(gr, gc, 0.0);
      }
  };
  for (int b = 0; b < nb; ++b) add_block(b, b);
  for (auto [hi, lo] : pairs) add_block(hi, lo);
  matrix.resize(n, n);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();

  auto slot = [&](int gr, int gc) {
    const int* rows = matrix.innerIndexPtr();
    const int begin = matrix.outerIndexPtr()[gc], end = matrix.outerIndexPtr()[gc + 1];
    return int(std::lower_bound(rows + begin, rows + end, gr) - rows);
  };
  auto block_slots = [&](int rb, int cb) {
    std::array<int, 36> s;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        const int gr = dof[rb][r], gc = dof[cb][c];
        s[r * 6 + c] = (gr >= 0 && gc >= 0 && gr >= gc) ? slot(gr, gc) : -1;
      }
    return s;
  };
  diag_slots.resize(nb);
  for (int b = 0; b < nb; ++b) diag_slots[b] = block_slots(b, b);
  off_slots.resize(pairs.size());
  for (size_t p = 0; p < pairs.size(); ++p) off_slots[p] = block_slots(pairs[p].first, pairs[p].second);

  diag.assign(nb, Mat6::Zero());
  second.assign(nb, Mat3::Zero());
  grad.assign(nb, Vec6::Zero());
  off.assign(pairs.size(), Mat6::Zero());

  supernodal->cholmod().print = 0;
  simplicial.cholmod().print = 0;
  if (factorization == Factorization::Automatic)
    factorization = n >= kSupernodalFromDofs ? Factorization::Supernodal : Factorization::Simplicial;
  if (n > 0) {
    if (supernodal_kind())
      supernodal->analyzePattern(matrix);
    else
      simplicial.analyzePattern(matrix);
  }
}

void GlobalSolver::Impl::assemble(const std::vector<BodyState>& state) {
  std::fill(diag.begin(), diag.end(), Mat6::Zero());
  std::fill(off.begin(), off.end(), Mat6::Zero());
  std::fill(second.begin(), second.end(), Mat3::Zero());
  std::fill(grad.begin(), grad.end(), Vec6::Zero());

  for (size_t ci = 0; ci < sys.couplings.size(); ++ci) {
    const RigidSystem::Coupling& c = sys.couplings[ci];
    const int b0 = c.body[0], b1 = c.body[1];
    if (!active[b0] && !active[b1]) continue;
    FeatureBlocks fb;
    for_each_residual(c, state[b0], state[b1], [&](const Vec3& y0, const Vec3& y1, const Vec3& r, double w,
                                     bool point) { fb.add(y0, y1, r, w, point); });

    diag[b0] += fb.h00;
    diag[b1] += fb.h11;
    grad[b0] += fb.g0;
    grad[b1] += fb.g1;
    second[b0] += fb.s0;
    second[b1] += fb.s1;
    const int p = coupling_pair[ci];
    if (p >= 0) {
      if (b0 == pairs[p].first) off[p] += fb.h01;
      else off[p] += fb.h01.transpose();
    }
  }

  for (const RigidSystem::Spring& s : sys.springs) {
    if (!active[s.body]) continue;
    const BodyState& st = state[s.body];
    FeatureBlocks fb;
    const Vec3 y = st.rotation * s.local;
    fb.add(y, Vec3::Zero(), y + st.position - s.target, s.weight, true);
    diag[s.body] += fb.h00;
    grad[s.body] += fb.g0;
    second[s.body] += fb.s0;
  }
}

void GlobalSolver::Impl::assemble_gradient(const std::vector<BodyState>& state) {
  // As FeatureBlocks::add, gradient rows only: w r for a point's translation, w y x r for
  // each rotation. A reused factor needs nothing else, so on the hierarchy's coarsest level
  // this runs twice a cycle: in parallel, each chunk of couplings into its own gradient,
  // added at the end (chunks fixed by the size, so the sums do not depend on the threads).
  auto add_couplings = [&](size_t begin, size_t end, std::vector<Vec6>& g) {
    for (size_t ci = begin; ci < end; ++ci) {
      const RigidSystem::Coupling& c = sys.couplings[ci];
      const int b0 = c.body[0], b1 = c.body[1];
      if (!active[b0] && !active[b1]) continue;
      for_each_residual(c, state[b0], state[b1],
                        [&](const Vec3& y0, const Vec3& y1, const Vec3& r, double w, bool point) {
                          if (point) {
                            g[b0].head<3>() += w * r;
                            g[b1].head<3>() -= w * r;
                          }
                          g[b0].tail<3>() += w * y0.cross(r);
                          g[b1].tail<3>() -= w * y1.cross(r);
                        });
    }
  };
  std::fill(grad.begin(), grad.end(), Vec6::Zero());
  // At most 8 chunks: each but the first sums into a gradient of its own, so more would cost
  // more memory traffic than they save.
  const size_t n = sys.couplings.size();
  const size_t chunks = chunk_count(n, std::max(kParallelGrain, n / 8));
  chunk_grad.resize(chunks - 1);
  parallel_tasks(chunks, [&](size_t k) {
    std::vector<Vec6>& g = k == 0 ? grad : chunk_grad[k - 1];
    if (k > 0) g.assign(grad.size(), Vec6::Zero());
    add_couplings(chunk_begin(n, chunks, k), chunk_begin(n, chunks, k + 1), g);
  });
  for (const std::vector<Vec6>& g : chunk_grad)  // in chunk order: the same bits on any threads
    for (size_t b = 0; b < grad.size(); ++b) grad[b] += g[b];
  for (const RigidSystem::Spring& s : sys.springs) {
    if (!active[s.body]) continue;
    const BodyState& st = state[s.body];
    const Vec3 y = st.rotation * s.local;
    const Vec3 r = y + st.position - s.target;
    grad[s.body].head<3>() += s.weight * r;
    grad[s.body].tail<3>() += s.weight * y.cross(r);
  }
}

void GlobalSolver::Impl::fill(SparseMatrix& target, double damping, bool with_second_order,
                              const std::vector<BodyState>& state) const {
  double* values = target.valuePtr();
  std::fill(values, values + target.nonZeros(), 0.0);
  for (int b = 0; b < sys.n_bodies(); ++b) {
    if (!active[b]) continue;
    Mat6 block = diag[b];
    if (with_second_order) block.block<3, 3>(3, 3) += second[b];
    if (damping > 0.0) {
      // Levenberg-Marquardt term in the body's own metric (its prism sides): it makes
      // bodies with nothing acting on them, and rigid modes of unanchored parts, solvable.
      const RigidSystem::Body& body = sys.bodies[b];
      const Mat3& R = state[b].rotation;
      const Vec3 first = R * (body.metric_weight * body.metric_mean);
      const Mat3 second_moment = R * body.metric_pinned * R.transpose();
      Mat6 metric = Mat6::Zero();
      metric.block<3, 3>(0, 0).diagonal().array() = body.metric_weight;
      metric.block<3, 3>(0, 3) = -cross_matrix(first);
      metric.block<3, 3>(3, 0) = cross_matrix(first);
      metric.block<3, 3>(3, 3) = -second_moment;
      metric.block<3, 3>(3, 3).diagonal().array() += second_moment.trace();
      block += damping * metric;
    }
    const auto& slots = diag_slots[b];
    for (int k = 0; k < 36; ++k)
      if (slots[k] >= 0) values[slots[k]] += block(k / 6, k % 6);
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto& slots = off_slots[p];
    for (int k = 0; k < 36; ++k)
      if (slots[k] >= 0) values[slots[k]] += off[p](k / 6, k % 6);
  }
}

std::pair<double, double> GlobalSolver::Impl::damping_and_scale() const {
  double trace_h = 0.0, trace_k = 0.0;
  for (int b = 0; b < sys.n_bodies(); ++b) {
    if (!active[b]) continue;
    trace_h += diag[b].trace();
    const auto& body = sys.bodies[b];
    trace_k += 3.0 * body.metric_weight + 2.0 * body.metric_pinned.trace();
  }
  // Tiny relative damping: invisible on well-posed problems, enough to make rank-deficient
  // ones factorizable. Raised when CHOLMOD still reports a non-positive pivot.
  const double scale = trace_k > 0 ? std::max(trace_h, 1e-300) / trace_k : 0.0;
  return {1e-10 * scale, scale};
}

bool GlobalSolver::Impl::factorize(double damping, bool with_second_order,
                                   const std::vector<BodyState>& state) {
  if (background.running) finish_background();  // `matrix` and the factors are ours again
  fill(matrix, damping, with_second_order, state);
  const auto start = Clock::now();
  bool ok;
  if (supernodal_kind()) {
    ScopedSingleThreadBlas scope(one_blas_thread());
    supernodal->factorize(matrix);
    ok = supernodal->info() == Eigen::Success;
    factorization_flops = supernodal->cholmod().fl;
  } else {
    simplicial.factorize(matrix);
    ok = simplicial.info() == Eigen::Success;
  }
  timings.factorization += seconds_since(start);
  ++timings.factorizations;
  if (!ok) ++timings.failed_factorizations;
  has_factor = ok;
  factor_exact = with_second_order;
  steps_on_factor = 0;
  if (ok) background.foreground_next = false;
  if (frames) factor_frames = *frames;
  return ok;
}

bool GlobalSolver::Impl::factorize_gauss_newton(double damping,
                                                const std::vector<BodyState>& state) {
  bool factored = factorize(damping, false, state);
  for (int retry = 0; !factored && retry < 6; ++retry) {
    damping = std::max(damping * 1e3, 1e-12);
    factored = factorize(damping, false, state);
  }
  return factored;
}

void GlobalSolver::Impl::start_background(const std::vector<BodyState>& state, bool exact) {
  Background& job = background;
  if (!job.spare) {
    job.spare = std::make_unique<SupernodalLLT>();
    job.spare->cholmod().print = 0;
    job.matrix = matrix;
  }
  const auto [damping, scale] = damping_and_scale();
  job.exact = exact && !job.exact_failed;  // after an indefinite one, Gauss-Newton
  if (frames) job.frames = *frames;
  fill(job.matrix, job.exact ? damping + exact_damping * scale : damping, job.exact, state);
  job.running = true;
  job.ready_at = steps + job.lag;
  const bool one_thread = one_blas_thread();
  try {
    job.thread = std::thread([&job, one_thread] {
      const auto start = Clock::now();
      job.ok = false;
      try {  // nothing may escape a thread (out of memory: the foreground refactorizes)
        ScopedSingleThreadBlas scope(one_thread);
        if (!job.spare_analyzed) {
          job.spare->analyzePattern(job.matrix);
          job.spare_analyzed = true;
        }
        job.spare->factorize(job.matrix);
        job.ok = job.spare->info() == Eigen::Success;
      } catch (...) {
      }
      job.seconds = seconds_since(start);
    });
  } catch (const std::system_error&) {  // no thread to be had: refresh in the foreground
    job.running = false;
    job.foreground_next = true;
  }
}

void GlobalSolver::Impl::finish_background() {
  Background& job = background;
  const auto start = Clock::now();
  job.thread.join();
  job.running = false;
  timings.factorization += seconds_since(start);  // only the wait shows in the foreground
  timings.background_factorization += job.seconds;
  ++timings.background_factorizations;
  job.exact_failed = !job.ok && job.exact;
  job.foreground_next = !job.ok && !job.exact;
  if (!job.ok) {
    ++timings.failed_factorizations;
    return;
  }
  std::swap(supernodal, job.spare);  // the old factor's object is analyzed too
  factor_frames.swap(job.frames);
  has_factor = true;
  factor_exact = job.exact;
  steps_on_factor = 0;
}

Eigen::VectorXd GlobalSolver::Impl::solve_corotated(const Eigen::VectorXd& rhs) {
  if (!frames || factor_frames.size() != frames->size()) return solve(rhs);
  // The old matrix is approximately T H T^T in today's frames, T the bodies' turns since; so
  // the step is T (old H)^-1 T^T rhs, each body's v and omega turned alike.
  auto turned = [&](const Eigen::VectorXd& x, bool forward) {
    Eigen::VectorXd y = x;
    for (int b = 0; b < sys.n_bodies(); ++b) {
      if (!active[b]) continue;
      const Mat3 t = (*frames)[b] * factor_frames[b].transpose();
      for (int part = 0; part < 2; ++part) {
        const int* d = &dof[b][3 * part];
        if (d[0] < 0) continue;  // masks keep or drop a whole v or omega
        const Vec3 v(x[d[0]], x[d[1]], x[d[2]]);
        const Vec3 w = forward ? Vec3(t * v) : Vec3(t.transpose() * v);
        for (int k = 0; k < 3; ++k) y[d[k]] = w[k];
      }
    }
    return y;
  };
  return turned(solve(turned(rhs, false)), true);
}

Eigen::VectorXd GlobalSolver::Impl::solve(const Eigen::VectorXd& rhs) {
  if (!supernodal_kind()) return simplicial.solve(rhs);
  ScopedSingleThreadBlas scope(one_blas_thread());
  return supernodal->solve(rhs);
}

std::vector<BodyState> GlobalSolver::Impl::apply(const std::vector<BodyState>& state,
                                                 const Eigen::VectorXd& delta, double lambda,
                                                 bool exponential) const {
  std::vector<BodyState> next = state;
  for (int b = 0; b < sys.n_bodies(); ++b) {
    if (!active[b]) continue;
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      if (dof[b][k] >= 0) v[k] = lambda * delta[dof[b][k]];
      if (dof[b][k + 3] >= 0) w[k] = lambda * delta[dof[b][k + 3]];
    }
    const BodyState& s = state[b];
    BodyState& t = next[b];
    const RigidSystem::Body& body = sys.bodies[b];
    if (exponential) {
      t.rotation = rotation_from_vector(w) * s.rotation;
      t.position = s.position + v;
      continue;
    }
    // Closest rigid motion to the affine map x -> x + w x (x - position) + v, measured on
    // the body's prism sides (paper Eq. 7): Horn on S = C (L R)^T with L = I + [w]x.
    const Mat3 LR = s.rotation + cross_matrix(w) * s.rotation;
    switch (body.kind) {
      case BodyKind::Free: {
        t.rotation = horn_rotation(body.metric_centered * LR.transpose(), s.rotation);
        const Vec3 arm = s.rotation * body.metric_mean;
        const Vec3 moved = s.position + arm + w.cross(arm) + v;
        t.position = moved - t.rotation * body.metric_mean;
        break;
      }
      case BodyKind::PinnedPosition:
        t.rotation = horn_rotation(body.metric_pinned * LR.transpose(), s.rotation);
        break;
      case BodyKind::FixedRotation:
        t.position = s.position + v;
        break;
      case BodyKind::Fixed:
        break;
    }
  }
  return next;
}

GlobalSolver::GlobalSolver(const RigidSystem& system, Factorization factorization)
    : impl_(std::make_unique<Impl>(system, factorization)) {
  impl_->build_pattern();
}

GlobalSolver::~GlobalSolver() = default;

int GlobalSolver::n_dofs() const { return impl_->n; }
double GlobalSolver::factorization_flops() const { return impl_->factorization_flops; }
bool GlobalSolver::has_factor() const { return impl_->has_factor; }

void GlobalSolver::set_body_frames(const std::vector<Mat3>* frames) {
  impl_->frames = frames;
  impl_->factor_frames.clear();
}

void GlobalSolver::set_factor_reuse(int max_reuse, int background_lag, int reused_step_halvings) {
  Impl& m = *impl_;
  m.max_reuse = std::max(max_reuse, 0);
  m.reused_step_halvings = std::max(reused_step_halvings, 0);
  m.background.lag = m.supernodal_kind() ? std::max(background_lag, 0) : 0;
}
const GlobalSolverTimings& GlobalSolver::timings() const { return impl_->timings; }
void GlobalSolver::reset_timings() { impl_->timings = {}; }

bool GlobalSolver::factorize_at(const std::vector<BodyState>& state) {
  Impl& m = *impl_;
  if (m.n == 0) return false;
  const auto start = Clock::now();
  m.assemble(state);
  m.timings.assembly += seconds_since(start);
  return m.factorize_gauss_newton(m.damping_and_scale().first, state);
}

GlobalStep GlobalSolver::iterate(std::vector<BodyState>& state, bool exact_hessian,
                                bool reuse_factorization) {
  Impl& m = *impl_;
  ++m.steps;
  if (m.background.running && m.steps >= m.background.ready_at) m.finish_background();
  GlobalStep step;
  step.energy_before = m.sys.energy(state);
  step.energy_after = step.energy_before;
  if (m.n == 0) return step;

  Eigen::VectorXd rhs(m.n);
  auto fill_rhs = [&] {
    for (int b = 0; b < m.sys.n_bodies(); ++b)
      for (int k = 0; k < 6; ++k)
        if (m.dof[b][k] >= 0) rhs[m.dof[b][k]] = -m.grad[b][k];
  };

  // Solve with the current factor and halve the step until the energy drops.
  auto search = [&](bool exact, int max_halvings) {
    auto solve_start = Clock::now();
    const Eigen::VectorXd delta = m.solve_corotated(rhs);
    m.timings.solve += seconds_since(solve_start);
    if (!delta.allFinite()) return false;
    const auto search_start = Clock::now();
    struct AddTime {
      double& total;
      Clock::time_point start;
      ~AddTime() { total += seconds_since(start); }
    } add_time{m.timings.line_search, search_start};
    std::vector<BodyState> trial;
    const HalvedStep found =
        halve_until_lower(m.sys, state, step.energy_before, max_halvings, trial,
                          [&](double lambda, std::vector<BodyState>& out) {
                            out = m.apply(state, delta, lambda, exact);
                          });
    m.timings.energy_evaluations += found.evaluations;
    if (found.lambda == 0.0) return false;
    step.energy_after = found.energy;
    step.step_scale = found.lambda;
    step.exact_hessian = exact;
    step.decreased = true;
    return true;
  };

  // A factor from an earlier iteration still gives a descent direction (the matrix it came
  // from is positive definite), and needs only the gradient; a few halvings at most
  // (set_factor_reuse) before paying for a fresh one.
  auto phase = Clock::now();
  bool assembled = false;  // the full system of `state` (not only its gradient)
  const bool spent = m.steps_on_factor > m.max_reuse;
  const bool in_background = m.background.lag > 0 && !m.background.foreground_next;
  if (reuse_factorization && m.has_factor && (!spent || in_background)) {
    if (spent && !m.background.running) {
      m.assemble(state);  // the matrix for the thread, and the gradient for this step
      assembled = true;
      m.start_background(state, exact_hessian);
    } else {
      m.assemble_gradient(state);
    }
    m.timings.assembly += seconds_since(phase);
    fill_rhs();
    auto reused_step = [&] {
      if (!search(m.factor_exact, m.reused_step_halvings)) return false;
      step.reused_factorization = true;
      ++m.steps_on_factor;
      return true;
    };
    if (reused_step()) return step;
    if (m.background.running) {  // the fresher factor now rather than a foreground one
      m.finish_background();
      if (m.has_factor && m.steps_on_factor == 0 && reused_step()) return step;
    }
    phase = Clock::now();
  }

  if (!assembled) {
    m.assemble(state);
    m.timings.assembly += seconds_since(phase);
    fill_rhs();
  }
  // Not a structured binding: C++17 lambdas cannot capture those (clang refuses; the fuzz build).
  double damping = 0.0, scale = 0.0;
  std::tie(damping, scale) = m.damping_and_scale();

  // One step of the given kind: factorize, solve, halve the step until the energy drops.
  auto try_step = [&](bool exact) {
    bool factored = false;
    if (exact) {
      // Indefinite far from the minimum: damp towards Gauss-Newton-like steps until positive
      // definite, and give up on exact steps for this iteration after a few tries.
      for (int attempt = 0; attempt < 4 && !factored; ++attempt) {
        factored = m.factorize(damping + m.exact_damping * scale, true, state);
        if (!factored) m.exact_damping = m.exact_damping == 0.0 ? 1e-4 : m.exact_damping * 30.0;
      }
      if (!factored) return false;
    } else if (!m.factorize_gauss_newton(damping, state)) {
      return false;
    }
    const bool ok = search(exact, 40);
    if (ok) ++m.steps_on_factor;
    if (exact) {
      if (ok && step.step_scale == 1.0)
        m.exact_damping = m.exact_damping < 1e-7 ? 0.0 : m.exact_damping / 10;
      else
        m.exact_damping = std::max(m.exact_damping * 10, 1e-4);
    }
    return ok;
  };
  if (exact_hessian && try_step(true)) return step;
  try_step(false);
  return step;
}

}  // namespace primo
