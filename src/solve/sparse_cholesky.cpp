#include "solve/sparse_cholesky.h"

#include <cholmod.h>
#include <dlfcn.h>
#include <omp.h>

#include <cmath>
#include <utility>

namespace periflex {

namespace {

// OpenBLAS built with threads (Debian's libopenblas0-pthread, when it is the BLAS installed)
// would start its own threads inside each dense block, competing with the solver's and with
// whatever else runs on the machine: the factorisation keeps to the calling thread.
void keep_blas_to_one_thread() {
  using SetThreads = void (*)(int);
  static const bool done = [] {
    if (void* f = dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) reinterpret_cast<SetThreads>(f)(1);
    return true;
  }();
  (void)done;
}

// CHOLMOD's supernodal factorisation opens OpenMP regions of a fixed four threads (to scatter
// the matrix into its blocks) whatever the program asked for: with another process on one of
// two cores, the first step of the notched plate took 95-120 ms of wall time for 65-75 ms of
// processor time, waiting at their barriers. Parallel regions are made inactive for the call.
class SerialOpenMp {
 public:
  SerialOpenMp() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMp() { omp_set_max_active_levels(levels_); }
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int levels_;
};

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  std::vector<int> start, rows;
  std::vector<double> values;
  cholmod_sparse matrix{};
  // solve workspace, kept between solves
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  bool factorized = false;

  Impl() {
    keep_blas_to_one_thread();
    cholmod_start(&common);
    common.print = 0;  // failures are returned, not printed
    common.error_handler = nullptr;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_ll = 1;
    // AMD alone: the nested-dissection orders CHOLMOD may also try take 20-30 ms on the plate's
    // matrix for 2% less fill
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_AMD;
    common.postorder = 1;
    // Relaxed supernodes: merging columns whose structures differ by up to 15-30% adds explicit
    // zeros but lets the BLAS work on larger blocks (factorisation of the plate's matrix
    // 35-40 ms against 55-60 ms with CHOLMOD's defaults of 4 / 16 / 48 and 0.8 / 0.1 / 0.05)
    common.nrelax[0] = 32;
    common.nrelax[1] = 128;
    common.nrelax[2] = 256;
    common.zrelax[0] = 0.9;
    common.zrelax[1] = 0.3;
    common.zrelax[2] = 0.15;
  }
  ~Impl() {
    free_solve_workspace();
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  void free_solve_workspace() {
    if (x) cholmod_free_dense(&x, &common);
    if (y) cholmod_free_dense(&y, &common);
    if (e) cholmod_free_dense(&e, &common);
  }
  // A view of the stored arrays as a CHOLMOD matrix (lower triangle stored).
  void describe(int n) {
    matrix = cholmod_sparse{};
    matrix.nrow = matrix.ncol = static_cast<size_t>(n);
    matrix.nzmax = rows.size();
    matrix.p = start.data();
    matrix.i = rows.data();
    matrix.x = values.data();
    matrix.stype = -1;
    matrix.itype = CHOLMOD_INT;
    matrix.xtype = CHOLMOD_REAL;
    matrix.dtype = CHOLMOD_DOUBLE;
    matrix.sorted = 1;
    matrix.packed = 1;
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyse(int n, const std::vector<int>& start, const std::vector<int>& rows) {
  Impl& s = *impl_;
  s.free_solve_workspace();
  if (s.factor) cholmod_free_factor(&s.factor, &s.common);
  s.factorized = false;
  s.start = start;
  s.rows = rows;
  s.values.assign(rows.size(), 0.0);
  s.describe(n);
  s.factor = cholmod_analyze(&s.matrix, &s.common);
}

bool SparseCholesky::analysed() const { return impl_->factor != nullptr; }

bool SparseCholesky::factorize(const double* values) {
  Impl& s = *impl_;
  s.factorized = false;
  if (!s.factor) return false;
  for (size_t k = 0; k < s.values.size(); ++k) {
    if (!std::isfinite(values[k])) return false;
    s.values[k] = values[k];
  }
  const SerialOpenMp serial;
  const int ok = cholmod_factorize(&s.matrix, s.factor, &s.common);
  // not positive definite: CHOLMOD stops at the failing column (minor < n) with a warning status
  s.factorized = ok && s.common.status == CHOLMOD_OK && s.factor->minor == s.factor->n;
  return s.factorized;
}

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  Impl& s = *impl_;
  const size_t n = static_cast<size_t>(b.size());
  cholmod_dense rhs{};
  rhs.nrow = n;
  rhs.ncol = 1;
  rhs.nzmax = n;
  rhs.d = n;
  rhs.x = const_cast<double*>(b.data());  // read only: cholmod_solve2 does not write B
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!s.factorized || s.factor->n != n || !cholmod_solve2(CHOLMOD_A, s.factor, &rhs, nullptr, &s.x, nullptr, &s.y, &s.e, &s.common)) {
    x = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(n), std::nan(""));  // the caller sees a failed solve
    return;
  }
  x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(s.x->x), static_cast<Eigen::Index>(n));
}

long SparseCholesky::factor_entries() const {
  const cholmod_factor* f = impl_->factor;
  if (!f || !impl_->factorized) return 0;
  // a supernodal factor stores dense blocks: count the entries of L they hold, relaxed zeros too
  return static_cast<long>(f->is_super ? f->xsize : f->nzmax);
}

}  // namespace periflex
