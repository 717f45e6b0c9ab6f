// The CVODE backend: BDF (orders 1-5) with Newton iterations on the model's exact (constant per
// mode) Jacobian, one internal step at a time (CV_ONE_STEP); the state inside the last step comes
// from the Nordsieck history (CVodeGetDky), where the driver looks for events and extremes. Each
// instance owns its SUNDIALS context, so simulations on several threads never share solver memory.
#include "ode_backend.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <stdexcept>

namespace mechgraph::valvetrain {
namespace {

class CvodeBackend final : public OdeBackend {
 public:
  CvodeBackend(const ChainModel& model, const SimulationOptions& options)
      : model_(model), options_(options), size_(static_cast<sunindextype>(2 * model.positions())) {
    if (SUNContext_Create(nullptr, &context_) != 0) throw std::runtime_error("CVODE: cannot create a SUNDIALS context");
    y_ = N_VNew_Serial(size_, context_);
    dky_ = N_VNew_Serial(size_, context_);
    atol_ = N_VNew_Serial(size_, context_);
    const sunindextype P = size_ / 2;
    for (sunindextype i = 0; i < size_; ++i) NV_Ith_S(atol_, i) = i < P ? options.atol_x : options.atol_v;
    matrix_ = SUNDenseMatrix(size_, size_, context_);
    solver_ = SUNLinSol_Dense(y_, matrix_, context_);
    memory_ = CVodeCreate(CV_BDF, context_);
    if (!y_ || !dky_ || !atol_ || !matrix_ || !solver_ || !memory_) {
      release();
      throw std::runtime_error("CVODE: out of memory");
    }
  }
  ~CvodeBackend() override { release(); }
  CvodeBackend(const CvodeBackend&) = delete;
  CvodeBackend& operator=(const CvodeBackend&) = delete;

  void restart(double t, const ChainState& s, const Mode& m) override {
    collect_work();
    for (sunindextype i = 0; i < size_; ++i) NV_Ith_S(y_, i) = s[static_cast<std::size_t>(i)];
    if (!initialised_) {
      check(CVodeInit(memory_, &CvodeBackend::rhs, t, y_), "CVodeInit");
      check(CVodeSetErrHandlerFn(memory_, &CvodeBackend::on_error, this), "CVodeSetErrHandlerFn");
      check(CVodeSetUserData(memory_, this), "CVodeSetUserData");
      check(CVodeSVtolerances(memory_, options_.rtol, atol_), "CVodeSVtolerances");
      check(CVodeSetLinearSolver(memory_, solver_, matrix_), "CVodeSetLinearSolver");
      check(CVodeSetJacFn(memory_, &CvodeBackend::jacobian), "CVodeSetJacFn");
      check(CVodeSetMaxNumSteps(memory_, options_.max_steps), "CVodeSetMaxNumSteps");
      if (options_.max_step > 0.0) check(CVodeSetMaxStep(memory_, options_.max_step), "CVodeSetMaxStep");
      initialised_ = true;
    } else {
      check(CVodeReInit(memory_, t, y_), "CVodeReInit");
    }
    if (!(m == mode_) || jacobian_.empty()) jacobian_ = model_.jacobian(m);
    mode_ = m;
    begin_ = end_ = t;
  }

  double step(double limit) override {
    error_.clear();
    check(CVodeSetStopTime(memory_, limit), "CVodeSetStopTime");
    advanced_ = true;
    sunrealtype t = 0.0;
    const int flag = CVode(memory_, limit, y_, &t, CV_ONE_STEP);
    if (flag < 0) check(flag, "CVode");
    begin_ = end_;
    end_ = flag == CV_TSTOP_RETURN ? limit : t;  // a stop at the limit ends exactly there
    return end_;
  }

  double step_begin() const override { return begin_; }

  void state_at(double t, ChainState& s) override {
    // Inside the last step from the Nordsieck history; at the step's end CVODE's own solution.
    N_Vector from = y_;
    if (t != end_) {
      error_.clear();
      check(CVodeGetDky(memory_, t, 0, dky_), "CVodeGetDky");
      from = dky_;
    }
    const sunrealtype* data = N_VGetArrayPointer(from);
    s.assign(data, data + size_);
  }

  void add_work(std::map<std::string, double>& work) const override {
    const_cast<CvodeBackend*>(this)->collect_work();
    for (const auto& [k, v] : totals_) work[k] += v;
    work["rhs_evaluations"] += static_cast<double>(rhs_count_);
    work["jacobian_evaluations"] += static_cast<double>(jacobian_count_);
  }

 private:
  ChainState state(N_Vector y) const {
    const sunrealtype* data = N_VGetArrayPointer(y);
    return ChainState(data, data + size_);
  }
  // The callbacks' view of CVODE's vector, in a buffer kept across calls (no allocation per call).
  const ChainState& view(N_Vector y) {
    const sunrealtype* data = N_VGetArrayPointer(y);
    scratch_.assign(data, data + size_);
    return scratch_;
  }
  static int rhs(sunrealtype t, N_Vector y, N_Vector dy, void* data) {
    auto* self = static_cast<CvodeBackend*>(data);
    ++self->rhs_count_;
    self->model_.rhs(self->mode_, t, self->view(y), self->derivative_);
    std::copy(self->derivative_.begin(), self->derivative_.end(), N_VGetArrayPointer(dy));
    return 0;
  }
  static int jacobian(sunrealtype, N_Vector, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<CvodeBackend*>(data);
    ++self->jacobian_count_;
    const auto n = static_cast<std::size_t>(self->size_);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = 0; c < n; ++c)
        SM_ELEMENT_D(J, static_cast<sunindextype>(r), static_cast<sunindextype>(c)) = self->jacobian_[r * n + c];
    return 0;
  }
  static void on_error(int, const char*, const char* function, char* message, void* data) {
    static_cast<CvodeBackend*>(data)->error_ = std::string(function) + ": " + message;
  }

  void check(int flag, const char* call) {
    if (flag >= 0) return;
    const std::string why = error_.empty() ? std::string(CVodeGetReturnFlagName(flag)) : error_;
    throw std::runtime_error("CVODE failed in " + std::string(call) + ": " + why);
  }

  // CVodeReInit zeroes CVODE's step counters, so each segment between restarts is added once
  // (a segment with no CVode call has nothing to add). Function evaluations are counted in the
  // callbacks themselves.
  void collect_work() {
    if (!advanced_) return;
    long steps = 0, failures = 0, nonlinear = 0;
    CVodeGetNumSteps(memory_, &steps);
    CVodeGetNumErrTestFails(memory_, &failures);
    CVodeGetNumNonlinSolvIters(memory_, &nonlinear);
    totals_["steps"] += static_cast<double>(steps);
    totals_["rejected_steps"] += static_cast<double>(failures);
    totals_["newton_iterations"] += static_cast<double>(nonlinear);
    advanced_ = false;
  }

  void release() {
    if (memory_) CVodeFree(&memory_);
    if (solver_) SUNLinSolFree(solver_);
    if (matrix_) SUNMatDestroy(matrix_);
    if (atol_) N_VDestroy(atol_);
    if (dky_) N_VDestroy(dky_);
    if (y_) N_VDestroy(y_);
    if (context_) SUNContext_Free(&context_);
  }

  const ChainModel& model_;
  SimulationOptions options_;
  sunindextype size_;
  std::vector<double> jacobian_;
  ChainState scratch_, derivative_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector dky_ = nullptr;  // the state inside the last step
  N_Vector atol_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
  void* memory_ = nullptr;
  bool initialised_ = false;
  Mode mode_{};
  double begin_ = 0.0, end_ = 0.0;  // the last step
  std::string error_;
  std::map<std::string, double> totals_;
  bool advanced_ = false;
  long rhs_count_ = 0, jacobian_count_ = 0;
};

}  // namespace

std::unique_ptr<OdeBackend> make_cvode_backend(const ChainModel& model, const SimulationOptions& options) {
  return std::make_unique<CvodeBackend>(model, options);
}

}  // namespace mechgraph::valvetrain
