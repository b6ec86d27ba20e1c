// The Python module `flagsim` (its C++ half, `flagsim._flagsim`; the package's
// __init__.py turns dicts into TOML and gives the names the contract lists).
//
// A Simulation is a scene compiled into a running simulation: step() advances
// it by output frames, positions / velocities / coarse_positions are numpy
// arrays that view the simulation's own buffers (read-only, no copy: they
// follow every step), run(path) writes the scene's whole run as `flag-sim run`
// would. infill() is the hybrid's infill alone, for an engine that simulates
// its own coarse cloth. Errors keep the command line's messages: a bad scene
// or argument is ValueError, a failed write OSError, a diverged frame
// RuntimeError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/infill/cell_grid.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/scene/scene.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/frame_runner.hpp"
#include "flagsim/sim/simulation.hpp"
#include "run_command.hpp"

namespace py = pybind11;

namespace flagsim::python {
namespace {

// A [rows, cols, 3] float64 array over `values` (row-major nodes), owned by `owner`, read-only.
py::array_t<double> node_view(std::span<const Vec3> values, int rows, int cols,
                              const py::object& owner) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  py::array_t<double> array(
      {py::ssize_t(rows), py::ssize_t(cols), py::ssize_t(3)},
      {py::ssize_t(cols * sizeof(Vec3)), py::ssize_t(sizeof(Vec3)), py::ssize_t(sizeof(double))},
      values.empty() ? nullptr : values.front().data(), owner);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

class PySimulation {
 public:
  /// @param toml_text  the scene (the embedded default when None)
  /// @param source     the name messages give it (the file's path, or "<scene text>")
  /// @param overrides  "KEY=VALUE" strings, as --set
  /// @param from_file  `source` is the file the text was read from (an input of run())
  PySimulation(std::optional<std::string> toml_text, std::string source,
               std::vector<std::string> overrides, bool from_file)
      : text_(toml_text ? *toml_text : std::string(default_scene_toml())),
        source_(toml_text ? std::move(source) : std::string(kDefaultSceneName)),
        from_file_(toml_text && from_file),
        overrides_(std::move(overrides)),
        scene_(parse_scene(text_, source_, overrides_)),
        simulation_(sim::make_simulation(scene_)) {}

  void step(int frames) {
    if (frames < 0) throw UserError(fmt_frames(frames));
    if (frames == 0) return;
    if (diverged_) throw std::runtime_error("the simulation diverged earlier: " + *diverged_);
    const sim::FrameRunResult result =
        sim::run_frames(*simulation_, scene_, frame_ + 1, frame_ + 1 + frames, {});
    frame_ = result.frame;  // the last frame made (no sinks, and Python raises no stop request)
    if (result.end == sim::FrameRunEnd::kDiverged) {
      diverged_ = fmt_diverged(describe(*result.divergence, scene_));
      throw std::runtime_error(*diverged_);
    }
  }
  double time() const { return frame_ / scene_.fps; }
  int frame() const { return frame_; }
  const Scene& scene() const { return scene_; }
  /// A copy of the whole state: continuing from it after set_state gives the same bytes.
  py::dict state() const;
  /// Continues from a state() of a simulation of the same scene (also one taken before a
  /// divergence: the divergence is forgotten).
  void set_state(const py::dict& state);
  const sim::Simulation& simulation() const { return *simulation_; }
  sim::Simulation& mutable_simulation() { return *simulation_; }
  std::pair<int, int> coarse_shape() const {
    const auto [rows, cols] = simulation_->coarse_indices();
    return {int(rows.size()), int(cols.size())};
  }
  /// The scene's whole run into `path`, as `flag-sim run SCENE -o PATH`.
  int run(const std::string& path, bool quiet) const {
    app::RunOptions options;
    options.scene_text = text_;
    if (from_file_) options.scene_path = source_;  // never written over, and named in messages
    options.sets = overrides_;
    options.output_path = path;
    options.quiet = quiet;
    return app::run_command(options);
  }

 private:
  static std::string fmt_frames(int frames) {
    return "step(frames=" + std::to_string(frames) + "): expected 0 or more frames";
  }
  std::string fmt_diverged(const std::string& why) const {
    return "diverged at t = " + std::to_string(time()) + " s (frame " + std::to_string(frame_) +
           "): " + why;
  }

  std::string text_, source_;
  bool from_file_;
  std::vector<std::string> overrides_;
  Scene scene_;
  std::unique_ptr<sim::Simulation> simulation_;
  int frame_ = 0;
  std::optional<std::string> diverged_;
};

// Names of a state's arrays: [rows, cols, 3] copies of the simulation's buffers.
constexpr const char* kStateFormat = "flagsim.state/1";

py::array_t<double> node_copy(std::span<const Vec3> values, int rows, int cols) {
  py::array_t<double> array({py::ssize_t(rows), py::ssize_t(cols), py::ssize_t(3)});
  std::copy_n(values.empty() ? nullptr : values.front().data(), values.size() * 3,
              array.mutable_data());
  return array;
}

// The entry `key` of a state dict as [n] nodes, checked against the shape [rows, cols, 3].
std::vector<Vec3> nodes_of(const py::dict& state, const char* key, int rows, int cols) {
  if (!state.contains(key))
    throw UserError(std::string("set_state: the state has no '") + key + "'");
  const auto array =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(state[key]);
  if (!array || array.ndim() != 3 || array.shape(0) != rows || array.shape(1) != cols ||
      array.shape(2) != 3)
    throw UserError(std::string("set_state: '") + key + "' must be an array of shape [" +
                    std::to_string(rows) + ", " + std::to_string(cols) + ", 3]");
  std::vector<Vec3> nodes(std::size_t(rows) * std::size_t(cols));
  std::copy_n(array.data(), nodes.size() * 3, nodes.front().data());
  for (const Vec3& x : nodes)
    if (!x.allFinite())
      throw UserError(std::string("set_state: '") + key + "' holds a value that is not finite");
  return nodes;
}

py::dict PySimulation::state() const {
  const sim::SimulationState s = simulation_->state();
  const Lattice& dense = simulation_->lattice();
  const auto [coarse_rows, coarse_cols] = coarse_shape();
  py::dict out;
  out["format"] = kStateFormat;
  out["frame"] = s.frame;
  out["time"] = s.physics.x_m.empty() ? frame_ / scene_.fps : s.physics.time_s;
  const bool hybrid = coarse_rows > 0;
  if (s.dense_m.empty()) {  // a full lattice: the physics' state is the dense one
    out["positions"] = node_copy(s.physics.x_m, dense.rows, dense.cols);
    out["velocities"] = node_copy(s.physics.v_m_s, dense.rows, dense.cols);
  } else {
    out["positions"] = node_copy(s.dense_m, dense.rows, dense.cols);
    out["velocities"] = node_copy(s.dense_v_m_s, dense.rows, dense.cols);
  }
  if (hybrid) {  // the coarse lattice's physics (before any slack the infill's nodes take)
    out["coarse_positions"] = node_copy(s.physics.x_m, coarse_rows, coarse_cols);
    out["coarse_velocities"] = node_copy(s.physics.v_m_s, coarse_rows, coarse_cols);
  }
  if (!s.infill_memory.empty())
    out["infill_memory"] =
        py::array_t<double>(py::ssize_t(s.infill_memory.size()), s.infill_memory.data());
  if (!s.physics.memory.empty())  // the creases' rest angles, rad
    out["physics_memory"] =
        py::array_t<double>(py::ssize_t(s.physics.memory.size()), s.physics.memory.data());
  if (s.wind) {  // the mean wind and how far it has carried the turbulence (set_wind)
    py::dict wind;
    wind["velocity"] = py::array_t<double>(3, s.wind->mean_m_s.data());
    wind["offset"] = py::array_t<double>(3, s.wind->offset_m.data());
    wind["since"] = s.wind->since_s;
    out["wind"] = wind;
  }
  return out;
}

// A 3-vector of the state's wind dict.
Vec3 wind_vector(const py::dict& wind, const char* key) {
  if (!wind.contains(key)) throw UserError(std::string("set_state: 'wind' has no '") + key + "'");
  const auto array =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(wind[key]);
  if (!array || array.ndim() != 1 || array.size() != 3)
    throw UserError(std::string("set_state: 'wind' '") + key + "' must have the shape [3]");
  Vec3 v(array.data()[0], array.data()[1], array.data()[2]);
  if (!v.allFinite()) throw UserError(std::string("set_state: 'wind' '") + key + "' is not finite");
  return v;
}

// The entry `key` of a state dict as `size` numbers (a memory the scene's `what` keeps).
std::vector<double> values_of(const py::dict& state, const char* key, std::size_t size,
                              const char* what) {
  if (!state.contains(key))
    throw UserError(std::string("set_state: the state has no '") + key + "' (this scene has " +
                    what + ")");
  const auto values =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(state[key]);
  if (!values || values.ndim() != 1 || std::size_t(values.size()) != size)
    throw UserError(std::string("set_state: '") + key + "' must be an array of shape [" +
                    std::to_string(size) + "]");
  return {values.data(), values.data() + values.size()};
}

void PySimulation::set_state(const py::dict& state) {
  if (!state.contains("format") || py::str(state["format"]).cast<std::string>() != kStateFormat)
    throw UserError(std::string("set_state: expected a dict from state() (format '") +
                    kStateFormat + "')");
  if (!state.contains("frame") || !state.contains("time"))
    throw UserError("set_state: the state has no 'frame' or 'time'");
  const int frame = state["frame"].cast<int>();
  const double time = state["time"].cast<double>();
  if (frame < 0 || !std::isfinite(time))
    throw UserError("set_state: 'frame' must be 0 or more and 'time' finite");
  const Lattice& dense = simulation_->lattice();
  const auto [coarse_rows, coarse_cols] = coarse_shape();
  const sim::SimulationState now = simulation_->state();
  sim::SimulationState s;
  s.frame = frame;
  std::vector<Vec3> x = nodes_of(state, "positions", dense.rows, dense.cols);
  std::vector<Vec3> v = nodes_of(state, "velocities", dense.rows, dense.cols);
  if (now.dense_m.empty()) {
    s.physics = {std::move(x), std::move(v), time};
  } else {
    s.dense_m = std::move(x);
    s.dense_v_m_s = std::move(v);
    if (coarse_rows > 0)
      s.physics = {nodes_of(state, "coarse_positions", coarse_rows, coarse_cols),
                   nodes_of(state, "coarse_velocities", coarse_rows, coarse_cols), time};
  }
  if (!now.infill_memory.empty())
    s.infill_memory = values_of(state, "infill_memory", now.infill_memory.size(), "wrinkles");
  if (!now.physics.memory.empty())
    s.physics.memory = values_of(state, "physics_memory", now.physics.memory.size(), "creases");
  if (state.contains("wind") && now.wind) {  // a state without one keeps the wind as it is
    const py::dict wind = state["wind"].cast<py::dict>();
    if (!wind.contains("since")) throw UserError("set_state: 'wind' has no 'since'");
    s.wind = physics::WindField::Drift{wind_vector(wind, "velocity"), wind_vector(wind, "offset"),
                                       wind["since"].cast<double>()};
  }
  simulation_->set_state(s);
  frame_ = frame;
  diverged_.reset();
}

// The hybrid's infill alone: dense positions [J, K, 3] from coarse ones [Jc, Kc, 3].
py::array_t<double> infill(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& coarse,
    std::pair<int, int> fine, std::pair<double, double> size, const std::string& pin,
    const std::string& solver) {
  if (coarse.ndim() != 3 || coarse.shape(2) != 3)
    throw UserError("infill: coarse must have the shape [Jc, Kc, 3] (m)");
  const int jc = int(coarse.shape(0)), kc = int(coarse.shape(1));
  const auto [j, k] = fine;
  if (jc < 2 || kc < 2 || j < jc || k < kc || (j - 1) % (jc - 1) != 0 || (k - 1) % (kc - 1) != 0)
    throw UserError("infill: fine=(" + std::to_string(j) + ", " + std::to_string(k) +
                    ") is not a refinement of the coarse lattice " + std::to_string(jc) + " x " +
                    std::to_string(kc) + " (each side's links a multiple of the coarse ones)");
  if (!(size.first > 0.0 && size.second > 0.0))
    throw UserError("infill: size=(width, height) must be positive lengths (m)");
  const std::optional<PinSet> pins = value_in(kPinNames, pin);
  if (!pins)
    throw UserError("infill: pin=\"" + pin + "\": expected left, right, top, corners or none");
  const std::optional<InfillSolverKind> kind = value_in(kInfillSolverNames, solver);
  if (!kind) throw UserError("infill: solver=\"" + solver + "\": expected smooth or paper");
  // The rest rectangle as a flag's: width along the rows, height down the columns.
  const Lattice lattice = Lattice::rectangle(j, k, size.first, size.second, Vec3::Zero());
  const infill::CellGrid grid = infill::CellGrid::of(lattice, jc, kc);
  infill::InfillOptions options;
  options.solver = *kind;
  const std::unique_ptr<infill::InfillMethod> method = infill::make_infill(lattice, grid, options);
  method->hold(physics::pinned_nodes(lattice, *pins));
  std::vector<Vec3> coarse_m(std::size_t(jc) * std::size_t(kc));
  const auto c = coarse.unchecked<3>();
  for (int a = 0; a < jc; ++a)
    for (int b = 0; b < kc; ++b)
      coarse_m[std::size_t(a) * std::size_t(kc) + std::size_t(b)] =
          Vec3(c(a, b, 0), c(a, b, 1), c(a, b, 2));
  // Starts from the rest lattice; the smooth infill depends on the coarse nodes alone.
  std::vector<Vec3> dense = lattice.rest_positions();
  method->fill(coarse_m, dense, nullptr);
  py::array_t<double> out({py::ssize_t(j), py::ssize_t(k), py::ssize_t(3)});
  auto o = out.mutable_unchecked<3>();
  for (int a = 0; a < j; ++a)
    for (int b = 0; b < k; ++b)
      for (int d = 0; d < 3; ++d)
        o(a, b, d) = dense[std::size_t(a) * std::size_t(k) + std::size_t(b)][d];
  return out;
}

}  // namespace
}  // namespace flagsim::python

PYBIND11_MODULE(_flagsim, m) {
  using flagsim::python::PySimulation;
  m.doc() = "flag-sim's simulations, from Python (the C++ half of the flagsim package)";
  py::register_exception<flagsim::UserError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<flagsim::IoError>(m, "WriteError", PyExc_OSError);
  py::class_<PySimulation>(m, "Simulation")
      .def(py::init<std::optional<std::string>, std::string, std::vector<std::string>, bool>(),
           py::arg("toml_text"), py::arg("source"), py::arg("overrides"),
           py::arg("from_file") = false)
      .def("step", &PySimulation::step, py::arg("frames") = 1)
      .def_property_readonly("time", &PySimulation::time)
      .def_property_readonly("frame", &PySimulation::frame)
      .def_property_readonly("fps", [](const PySimulation& s) { return s.scene().fps; })
      .def_property_readonly(
          "mode", [](const PySimulation& s) { return std::string(to_string(s.scene().mode)); })
      .def_property_readonly("shape",
                             [](const PySimulation& s) {
                               const flagsim::Lattice& l = s.simulation().lattice();
                               return std::pair<int, int>(l.rows, l.cols);
                             })
      .def_property_readonly("positions",
                             [](const py::object& self) {
                               const PySimulation& s = self.cast<const PySimulation&>();
                               const flagsim::Lattice& l = s.simulation().lattice();
                               return flagsim::python::node_view(s.simulation().positions(), l.rows,
                                                                 l.cols, self);
                             })
      .def_property_readonly("velocities",
                             [](const py::object& self) {
                               const PySimulation& s = self.cast<const PySimulation&>();
                               const flagsim::Lattice& l = s.simulation().lattice();
                               return flagsim::python::node_view(s.simulation().velocities(),
                                                                 l.rows, l.cols, self);
                             })
      .def_property_readonly("coarse_positions",
                             [](const py::object& self) -> py::object {
                               const PySimulation& s = self.cast<const PySimulation&>();
                               const auto [rows, cols] = s.coarse_shape();
                               if (rows == 0) return py::none();
                               return flagsim::python::node_view(s.simulation().coarse_positions(),
                                                                 rows, cols, self);
                             })
      .def_property(
          "wind",
          [](const PySimulation& s) -> py::object {
            const std::optional<flagsim::Vec3> wind = s.simulation().wind();
            if (!wind) return py::none();
            return py::array_t<double>(3, wind->data());
          },
          [](PySimulation& s, const std::array<double, 3>& v) {
            s.mutable_simulation().set_wind(flagsim::Vec3(v[0], v[1], v[2]));
          },
          "The mean wind [x, y, z], m/s (None without [wind]); settable between steps, up to "
          "the scene's wind speed")
      .def("state", &PySimulation::state)
      .def("set_state", &PySimulation::set_state, py::arg("state"))
      .def("run", &PySimulation::run, py::arg("path"), py::arg("quiet") = true);
  m.def("infill", &flagsim::python::infill, py::arg("coarse"), py::arg("fine"),
        py::arg("size") = std::pair<double, double>(1.5, 1.0), py::arg("pin") = "left",
        py::arg("solver") = "smooth");
}
