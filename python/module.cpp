// The compiled core of the Python package `grains` (pybind11): cases,
// simulations stepped from Python, zero-copy numpy views of the particle
// store, checkpoints. docs/python.md is the user's guide; grains/__init__.py
// adds the pure-Python helpers.
#include <pybind11/functional.h>
#include <pybind11/iostream.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <charconv>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <omp.h>

#include "grains/version.hpp"
#include "io/case/case.hpp"
#include "io/checkpoint/checkpoint.hpp"
#include "io/output/progress.hpp"
#include "io/run/allocator.hpp"
#include "io/run/simulation.hpp"
#include "postprocess/analysis.hpp"
#include "sim/integrate/arkode.hpp"
#include "sim/neighbor/neighbor_stage.hpp"
#include "sim/neighbor/whole_clumps.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"
#include "sim/scene/build_scene.hpp"

namespace py = pybind11;
using namespace grains;

namespace {

// ---------------------------------------------------------------- YAML <-> Python

// A YAML scalar as the Python value it reads as: int, float, bool, None or str.
py::object scalar_to_py(const YAML::Node& n) {
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") return py::str(s);  // quoted in the file: a string
  if (s == "~" || s == "null" || s == "Null" || s == "NULL") return py::none();
  if (s == "true" || s == "True" || s == "TRUE") return py::bool_(true);
  if (s == "false" || s == "False" || s == "FALSE") return py::bool_(false);
  {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (!s.empty() && end == s.c_str() + s.size() && errno == 0) return py::int_(v);
  }
  {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (!s.empty() && end == s.c_str() + s.size()) return py::float_(v);
  }
  return py::str(s);
}

py::object yaml_to_py(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: {
      py::dict d;
      for (const auto& kv : n) d[py::str(kv.first.Scalar())] = yaml_to_py(kv.second);
      return d;
    }
    case YAML::NodeType::Sequence: {
      py::list l;
      for (const auto& e : n) l.append(yaml_to_py(e));
      return l;
    }
    case YAML::NodeType::Scalar:
      return scalar_to_py(n);
    default:
      return py::none();
  }
}

std::string number_text(double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // the shortest text that reads back as v
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // stays a float
  return s;
}

// Emits a Python value (dicts, lists, tuples, numpy arrays, numbers, bools,
// strings, None) as YAML; `where` names it in errors (a key path).
void py_to_yaml(YAML::Emitter& e, py::handle h, const std::string& where) {
  if (h.is_none()) {
    e << YAML::Null;
  } else if (py::isinstance<py::bool_>(h) || py::isinstance(h, py::module_::import("numpy").attr("bool_"))) {
    e << (h.cast<bool>() ? "true" : "false");
  } else if (py::isinstance<py::int_>(h) || py::isinstance(h, py::module_::import("numpy").attr("integer"))) {
    e << py::str(py::int_(py::reinterpret_borrow<py::object>(h))).cast<std::string>();
  } else if (py::isinstance<py::float_>(h) || py::isinstance(h, py::module_::import("numpy").attr("floating"))) {
    e << number_text(py::float_(py::reinterpret_borrow<py::object>(h)).cast<double>());
  } else if (py::isinstance<py::str>(h)) {
    e << YAML::DoubleQuoted << h.cast<std::string>();
  } else if (py::isinstance<py::dict>(h)) {
    e << YAML::BeginMap;
    for (auto kv : py::reinterpret_borrow<py::dict>(h)) {
      if (!py::isinstance<py::str>(kv.first))
        throw py::type_error(where + ": a case's keys are strings, not " +
                             py::str(py::type::of(kv.first).attr("__name__")).cast<std::string>());
      const std::string k = kv.first.cast<std::string>();
      e << YAML::Key << k << YAML::Value;
      py_to_yaml(e, kv.second, where.empty() ? k : where + "." + k);
    }
    e << YAML::EndMap;
  } else if (py::isinstance<py::list>(h) || py::isinstance<py::tuple>(h) || py::isinstance<py::array>(h)) {
    py::list l = py::isinstance<py::array>(h) ? py::list(h.attr("tolist")()) : py::list(py::reinterpret_borrow<py::object>(h));
    e << YAML::Flow << YAML::BeginSeq;
    std::size_t k = 0;
    for (auto x : l) py_to_yaml(e, x, where + "." + std::to_string(k++));
    e << YAML::EndSeq;
  } else {
    throw py::type_error((where.empty() ? std::string("the case") : where) + ": cannot put a " +
                         py::str(py::type::of(h).attr("__name__")).cast<std::string>() +
                         " in a case (use dicts, lists, numbers, bools and strings)");
  }
}

std::string yaml_text(py::handle h, const std::string& where) {
  YAML::Emitter e;
  py_to_yaml(e, h, where);
  return e.c_str();
}

// ---------------------------------------------------------------- Case

// A case: its text, where relative paths start, and the edits made to it,
// validated together at every change.
struct PyCase {
  std::string text, name, base_dir;
  std::vector<std::string> overrides;
  io::Case c;

  void parse() { c = io::parse_case(text, name, overrides, base_dir); }

  static PyCase from_file(const std::string& path, const std::vector<std::string>& set) {
    PyCase p;
    p.c = io::load_case(path, set);
    p.text = p.c.text;
    p.name = path;
    p.base_dir = p.c.base_dir;
    p.overrides = set;
    return p;
  }
  static PyCase from_text(const std::string& text, const std::string& name, const std::string& base_dir,
                          const std::vector<std::string>& set) {
    PyCase p;
    p.text = text;
    p.name = name;
    p.base_dir = base_dir;
    p.overrides = set;
    p.parse();
    return p;
  }
  // One edit, as --set key=value: kept only if the case stays valid.
  void set(const std::string& key, py::handle value) {
    if (key.empty() || key.find('=') != std::string::npos)
      throw py::key_error("a case key is a dotted path such as 'time.end' or 'materials.0.friction', not '" + key + "'");
    YAML::Emitter e;
    e << YAML::Flow;
    py_to_yaml(e, value, key);
    overrides.push_back(key + "=" + e.c_str());
    try {
      parse();
    } catch (...) {
      overrides.pop_back();
      parse();
      throw;
    }
  }
  py::object get(const std::string& key) const {
    YAML::Node cur = YAML::Clone(c.root);
    std::stringstream ss(key);
    for (std::string p; std::getline(ss, p, '.');) {
      YAML::Node next;
      if (cur.IsSequence()) {
        char* end = nullptr;
        const long k = std::strtol(p.c_str(), &end, 10);
        if (end == p.c_str() + p.size() && k >= 0 && static_cast<std::size_t>(k) < cur.size()) next = cur[k];
      } else if (cur.IsMap()) {
        next = cur[p];
      }
      if (!next) throw py::key_error("the case has no '" + key + "' (no '" + p + "')");
      cur.reset(next);
    }
    return yaml_to_py(cur);
  }
  std::string effective_text() const {
    YAML::Emitter e;
    e << c.root;
    return e.c_str();
  }
};

// ---------------------------------------------------------------- Simulation

// The base object of every numpy view: keeps the simulation alive while the
// view lives, and, once the view is detached (the simulation stepped while it
// was alive), the buffer it points into.
struct ViewGuard {
  py::object owner;
  std::shared_ptr<void> kept;
};

// A per-particle array of the store a view can show.
struct FieldRef {
  const char* name;
  void* (*data)(sim::ParticleStore&);
  std::size_t (*size)(sim::ParticleStore&);  // entries allocated (0: the field is absent)
  // Moves the field's buffer out (to a view that keeps it) and gives the
  // store a copy.
  std::shared_ptr<void> (*take)(sim::ParticleStore&);
  char kind;           // 'd' double, 'q' int64, 'i' int32
  int width;           // numbers per particle
  bool writable;       // users may write it (validated before the next step)
  const char* absent;  // why a scene lacks it
};

template <class T, std::vector<T> sim::ParticleStore::*M>
void* field_data(sim::ParticleStore& p) {
  return static_cast<void*>((p.*M).data());
}
template <class T, std::vector<T> sim::ParticleStore::*M>
std::size_t field_size(sim::ParticleStore& p) {
  return (p.*M).size();
}
template <class T, std::vector<T> sim::ParticleStore::*M>
std::shared_ptr<void> field_take(sim::ParticleStore& p) {
  auto kept = std::make_shared<std::vector<T>>(std::move(p.*M));
  p.*M = *kept;
  return kept;
}

#define GRAINS_FIELD(nm, member, T, kind, width, writable, absent) \
  FieldRef{nm, &field_data<T, &sim::ParticleStore::member>, &field_size<T, &sim::ParticleStore::member>, \
           &field_take<T, &sim::ParticleStore::member>, kind, width, writable, absent}

const std::vector<FieldRef>& field_refs() {
  static const std::vector<FieldRef> f = {
      GRAINS_FIELD("positions", x, sim::Vec3, 'd', 3, true, ""),
      GRAINS_FIELD("velocities", v, sim::Vec3, 'd', 3, true, ""),
      GRAINS_FIELD("forces", f, sim::Vec3, 'd', 3, false, ""),
      GRAINS_FIELD("radii", radius, double, 'd', 1, false, ""),
      GRAINS_FIELD("masses", mass, double, 'd', 1, false, ""),
      GRAINS_FIELD("ids", id, std::int64_t, 'q', 1, false, ""),
      GRAINS_FIELD("materials", material, std::int32_t, 'i', 1, false, ""),
      GRAINS_FIELD("angular_velocities", omega, sim::Vec3, 'd', 3, true,
                   "the scene's grains do not rotate (no tangential or rolling law, no ellipsoids or clumps)"),
      GRAINS_FIELD("torques", torque, sim::Vec3, 'd', 3, false, "the scene's grains do not rotate"),
      GRAINS_FIELD("orientations", orientation, sim::Quat, 'd', 4, false,
                   "the scene has no ellipsoids (spheres and clump balls carry no orientation)"),
      GRAINS_FIELD("semi_axes", semi_axes, sim::Vec3, 'd', 3, false, "the scene has no ellipsoids"),
      GRAINS_FIELD("body_ids", body, std::int64_t, 'q', 1, false, "the scene has no clumps"),
  };
  return f;
}
#undef GRAINS_FIELD

const FieldRef& field_ref(const std::string& name) {
  for (const auto& f : field_refs())
    if (name == f.name) return f;
  throw py::key_error("no particle field '" + name + "'");
}

struct Live {
  py::weakref array;
  std::string field;
  py::weakref guard;  // its ViewGuard (the array holds it)
};

struct PySim {
  std::unique_ptr<io::Simulation> sim;
  std::unique_ptr<io::Runner> runner;
  io::RunOptions opt;
  std::vector<Live> views;  // views handed out since the last change
  bool written = false;     // a writable view was handed out: validate before stepping
  bool closed = false;
  py::object summary = py::none();

  // ARKODE keeps the state in its own vector between steps (it reads the
  // store again only when the neighbour lists are rebuilt).
  static constexpr const char* kArkodeState =
      "the ARKODE integrator holds the grains' state in its own vector between steps, so it cannot be written "
      "from Python; use time.integrator: verlet for a scene a script edits";
  bool arkode() const { return sim->c.scene.integrator == sim::Integrator::Arkode; }

  void check_open() const {
    if (closed) throw std::logic_error("the simulation is closed: make a new one (or continue from its checkpoint)");
  }
  sim::Scene& scene() { return sim->scene; }

  // The views alive now become read-only snapshots that own their memory:
  // the store's buffer moves to them and the store continues on a copy.
  void detach_views() {
    auto& p = scene().particles;
    std::vector<std::pair<std::string, std::shared_ptr<void>>> moved;
    for (auto& l : views) {
      py::object a = l.array();
      if (a.is_none()) continue;  // the array is gone
      std::shared_ptr<void> keep;
      for (auto& m : moved)
        if (m.first == l.field) keep = m.second;
      if (!keep) {
        keep = field_ref(l.field).take(p);
        moved.emplace_back(l.field, keep);
      }
      py::object g = l.guard();
      if (!g.is_none()) g.cast<ViewGuard&>().kept = keep;
      a.attr("flags").attr("writeable") = false;
    }
    views.clear();
  }

  // Values written through views are checked before the physics sees them.
  void validate_writes() {
    if (!written) return;
    auto& p = scene().particles;
    const std::size_t n = p.n_owned();
    auto check = [&](const std::vector<sim::Vec3>& a, const char* name) {
      if (a.empty()) return;
      for (std::size_t i = 0; i < n; ++i)
        if (!a[i].allFinite())
          throw py::value_error(std::string(name) + " of grain " + std::to_string(p.id[i]) + " (row " +
                                std::to_string(i) + ") is not finite: write finite values before stepping");
    };
    check(p.x, "the position");
    check(p.v, "the velocity");
    check(p.omega, "the angular velocity");
    const auto& d = scene().domain;
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k)
        if (!d.periodic[k] && (p.x[i][k] < d.lo[k] || p.x[i][k] > d.hi[k]))
          throw py::value_error("the position of grain " + std::to_string(p.id[i]) + " (row " + std::to_string(i) +
                                ") is outside the domain along " + "xyz"[k] + ": write positions inside it");
    // Moved grains need nothing more: the neighbour stage's trigger
    // compares every position with the one at the last build, so a grain
    // written more than half the skin away rebuilds the lists next step.
    written = false;
  }

  // Before the state changes: check what was written, detach the views.
  void before_change() {
    check_open();
    validate_writes();
    detach_views();
  }

  py::array view(py::object self, const std::string& field, bool writable_request) {
    check_open();
    const FieldRef& f = field_ref(field);
    auto& p = scene().particles;
    if (f.size(p) == 0) throw py::attribute_error(std::string("no ") + f.name + ": " + f.absent);
    const bool clump_ball = !p.body.empty() && (field == "positions" || field == "velocities" ||
                                                field == "angular_velocities");
    const bool writable = f.writable && writable_request && !clump_ball && !arkode();
    const auto n = static_cast<py::ssize_t>(p.n_owned());
    std::vector<py::ssize_t> shape{n}, strides;
    py::dtype dt = f.kind == 'd' ? py::dtype::of<double>() : f.kind == 'q' ? py::dtype::of<std::int64_t>()
                                                                             : py::dtype::of<std::int32_t>();
    const py::ssize_t item = dt.itemsize();
    if (f.width > 1) {
      shape.push_back(f.width);
      strides = {item * f.width, item};
    } else {
      strides = {item};
    }
    py::object guard = py::cast(ViewGuard{self, nullptr});
    py::array a(dt, shape, strides, f.data(p), guard);
    if (!writable) a.attr("flags").attr("writeable") = false;
    if (writable) written = true;
    views.push_back(Live{py::weakref(a), field, py::weakref(guard)});
    return a;
  }

  void write(const std::string& field, py::handle values) {
    check_open();
    const FieldRef& f = field_ref(field);
    auto& p = scene().particles;
    if (f.size(p) == 0) throw py::attribute_error(std::string("no ") + f.name + ": " + f.absent);
    if (!f.writable) throw py::value_error(std::string(f.name) + " cannot be written");
    if (arkode()) throw py::value_error(std::string(f.name) + ": " + kArkodeState);
    if (!p.body.empty())
      throw py::value_error(std::string(f.name) + " of clump balls follow their bodies and cannot be written");
    py::array in = py::array::ensure(values);
    if (!in) throw py::type_error(std::string(f.name) + ": expected an array of numbers");
    const char k = in.dtype().kind();
    if (k != 'f' && k != 'i' && k != 'u')
      throw py::type_error(std::string(f.name) + ": expected real numbers, got an array of dtype " +
                           py::str(in.dtype()).cast<std::string>());
    const auto n = static_cast<py::ssize_t>(p.n_owned());
    if (in.ndim() != 2 || in.shape(0) != n || in.shape(1) != f.width)
      throw py::value_error(std::string(f.name) + ": expected shape (" + std::to_string(n) + ", " +
                            std::to_string(f.width) + "), got " + py::str(in.attr("shape")).cast<std::string>());
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(in);
    auto r = d.unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
      for (int c = 0; c < f.width; ++c)
        if (!std::isfinite(r(i, c)))
          throw py::value_error(std::string(f.name) + ": row " + std::to_string(i) + " (grain " +
                                std::to_string(p.id[i]) + ") is not finite; nothing was written");
    if (field == "positions") {
      const auto& dom = scene().domain;
      for (py::ssize_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          if (!dom.periodic[c] && (r(i, c) < dom.lo[c] || r(i, c) > dom.hi[c]))
            throw py::value_error("positions: row " + std::to_string(i) + " (grain " + std::to_string(p.id[i]) +
                                  ") is outside the domain along " + "xyz"[c] + "; nothing was written");
    }
    auto* out = static_cast<double*>(f.data(p));
    for (py::ssize_t i = 0; i < n; ++i)
      for (int c = 0; c < f.width; ++c) out[i * f.width + c] = r(i, c);
  }

  // Grains out or in: the lists and ghosts are rebuilt at once (the
  // contact histories follow their pairs by global ids).
  void rebuild() {
    sim::NeighborStage::full_update(scene(), sim->c.scene.sort_particles);
  }

  // Removes this rank's grains whose flag is set (clumps: whole bodies); collective.
  std::int64_t remove(const std::vector<char>& flag) {
    auto& sc = scene();
    auto& p = sc.particles;
    std::vector<char> out(flag.begin(), flag.end());
    sim::flag_whole_clumps(sc, out);  // a clump goes as a whole when any of its balls is picked
    std::int64_t n = 0;
    for (char c : out) n += c ? 1 : 0;
    p.clear_ghosts();
    p.remove_if(out);
    rebuild();
    return sim::Comm::world().sum(n);
  }

  // Adds grains of particle set `set` (spheres, ellipsoids or clumps of
  // bounding radius r), each on the rank that owns its centre, as the
  // insertion stage does; collective. Refused when one overlaps a grain or
  // another new one (bounding spheres), or lies outside the domain.
  std::int64_t insert(const std::vector<sim::Vec3>& x, const std::vector<double>& r, const std::vector<sim::Vec3>& v,
                      const std::vector<sim::Quat>& q, std::size_t set_index) {
    auto& sc = scene();
    auto& cfg = sim->c.scene;
    const auto& comm = sim::Comm::world();
    if (set_index >= cfg.sets.size())
      throw py::value_error("insert: the case has " + std::to_string(cfg.sets.size()) + " particle set(s); set=" +
                            std::to_string(set_index) + " is not one of them");
    const auto& set = cfg.sets[set_index];
    const bool clump = set.shape.kind == sim::ShapeConfig::Kind::Clump;
    auto& p = sc.particles;
    const double bound = set.shape.kind == sim::ShapeConfig::Kind::Ellipsoid ? set.shape.axes_rel.maxCoeff() : 1.0;
    std::string err;
    for (std::size_t k = 0; k < x.size() && err.empty(); ++k) {
      bool inside = sc.domain.contains(x[k]);
      if (clump)  // its balls: within its bounding sphere
        for (int d = 0; d < 3; ++d)
          inside = inside && (sc.domain.periodic[d] ||
                              (x[k][d] - r[k] >= sc.domain.lo[d] && x[k][d] + r[k] <= sc.domain.hi[d]));
      if (!inside) {
        err = "insert: row " + std::to_string(k) + " lies outside the domain";
        break;
      }
      const double rk = r[k] * bound;
      // Every rank checks its own grains, through the periodic faces too (not
      // every image is kept between builds), and the ghosts it holds.
      for (std::size_t i = 0; i < p.size() && err.empty(); ++i)
        if ((i < p.n_owned() ? sc.domain.nearest_image(p.x[i] - x[k], sc.clock.time) : sim::Vec3(p.x[i] - x[k])).norm() <
            rk + p.radius[i])
          err = "insert: row " + std::to_string(k) + " overlaps grain " + std::to_string(p.id[i]) +
                "; nothing was inserted";
      for (std::size_t j = 0; j < k && err.empty(); ++j)
        if (sc.domain.nearest_image(x[j] - x[k], sc.clock.time).norm() < rk + r[j] * bound)
          err = "insert: rows " + std::to_string(j) + " and " + std::to_string(k) + " overlap; nothing was inserted";
    }
    if (comm.agree_error(err)) throw py::value_error(err);
    std::int64_t gid = 0, body = 0;
    for (std::size_t i = 0; i < p.n_owned(); ++i) gid = std::max(gid, p.id[i] + 1);
    for (auto b : sc.bodies.id) body = std::max(body, b + 1);
    gid = comm.max(gid);
    body = comm.max(body);
    const std::int64_t balls = clump ? static_cast<std::int64_t>(set.shape.clump->radii.size()) : 1;
    p.clear_ghosts();
    const bool ellipsoid_fields = p.fields().has(sim::Field::SemiAxes);
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (!sc.exchange || sc.exchange->decomposition().owner(x[k]) == comm.rank()) {
        const auto before = p.n_owned();
        std::int64_t id = gid;
        sim::add_grain(sc, set, x[k], r[k], q[k], id, clump ? body : -1, ellipsoid_fields, "an inserted grain");
        for (auto i = before; i < p.n_owned(); ++i) p.v[i] = v[k];
        if (clump) sc.bodies.v.back() = v[k];
      }
      gid += balls;
      if (clump) ++body;
    }
    rebuild();
    return static_cast<std::int64_t>(x.size());
  }

  // New sliding, rolling friction, restitution or cohesion of a material,
  // between steps: the pair table is mixed again.
  void set_material(const std::string& name, py::kwargs values) {
    auto& cfg = sim->c.scene;
    auto& sc = scene();
    int m = -1;
    for (std::size_t k = 0; k < cfg.materials.size(); ++k)
      if (cfg.materials[k].name == name) m = static_cast<int>(k);
    if (m < 0) {
      std::string names;
      for (const auto& mat : cfg.materials) names += (names.empty() ? "" : ", ") + mat.name;
      throw py::key_error("no material '" + name + "' (the case has: " + names + ")");
    }
    sim::Material mat = cfg.materials[static_cast<std::size_t>(m)];
    for (auto kv : values) {
      const std::string k = kv.first.cast<std::string>();
      const double x = kv.second.cast<double>();
      if (!std::isfinite(x) || x < 0) throw py::value_error("set_material: " + k + " must be finite and >= 0");
      if (k == "friction") mat.friction = x;
      else if (k == "rolling_friction") mat.rolling_friction = x;
      else if (k == "restitution") {
        if (x <= 0 || x > 1) throw py::value_error("set_material: restitution must be in (0, 1]");
        mat.restitution = x;
      } else if (k == "cohesion") mat.cohesion = x;
      else
        throw py::key_error("set_material: '" + k + "' cannot change between steps (friction, rolling_friction, "
                            "restitution and cohesion can; the stiffness and density set the time step and masses)");
    }
    auto mats = cfg.materials;
    mats[static_cast<std::size_t>(m)] = mat;
    sim::PairTable table(mats, cfg.overrides, cfg.normal);
    const auto before = sim::scene_needs(cfg, sc.pairs), after = sim::scene_needs(cfg, table);
    auto missing = [](bool had, bool needs, const char* what) {
      if (needs && !had)
        throw py::value_error(std::string("set_material: the scene was built without ") + what +
                              " (an absent effect runs no code); give it a nonzero value in the case to change it "
                              "between stages");
    };
    missing(before.tangential, after.tangential, "sliding friction");
    missing(before.rolling, after.rolling, "rolling friction");
    missing(before.cohesion, after.cohesion, "cohesion");
    cfg.materials = mats;
    sc.materials = mats;
    sc.pairs = std::move(table);
  }

  // A wall's motion between steps: a plane's or a cylinder's velocity; a
  // mesh wall's velocity, rotation speed and vibration, continued from its
  // pose now (MeshWall::rebase). The lists are rebuilt (their trigger
  // bounds a wall's travel by its speed since the last build, which a
  // slower wall would no longer bound).
  struct WallMotion {
    std::optional<sim::Vec3> velocity;
    std::optional<double> angular_velocity, vibration_frequency;
    std::optional<sim::Vec3> vibration_amplitude;
  };
  void set_wall_motion(const std::string& name, const WallMotion& m) {
    auto& sc = scene();
    const auto finite = [](const char* what, const auto& o) {
      bool ok = true;
      if constexpr (std::is_same_v<std::decay_t<decltype(*o)>, double>)
        ok = !o || std::isfinite(*o);
      else
        ok = !o || o->allFinite();
      if (!ok) throw py::value_error(std::string("set_wall_motion: ") + what + " must be finite");
    };
    finite("velocity", m.velocity);
    finite("angular_velocity", m.angular_velocity);
    finite("vibration_amplitude", m.vibration_amplitude);
    finite("vibration_frequency", m.vibration_frequency);
    if (m.vibration_frequency && *m.vibration_frequency < 0)
      throw py::value_error("set_wall_motion: vibration_frequency must be >= 0 (Hz)");
    if (arkode())
      throw py::value_error("set_wall_motion: the ARKODE integrator moves the walls by the motion they had at "
                            "its start; use time.integrator: verlet for a scene a script edits");
    const auto stages = sim->pipeline.stage_names();
    const bool moves = std::any_of(stages.begin(), stages.end(), [](const std::string& n) {
      return n.size() >= 10 && n.compare(n.size() - 10, 10, "walls.move") == 0;  // ("drift: walls.move")
    });
    const bool still = (!m.velocity || m.velocity->squaredNorm() == 0) && m.angular_velocity.value_or(0) == 0 &&
                       (!m.vibration_amplitude || m.vibration_amplitude->squaredNorm() == 0 ||
                        m.vibration_frequency.value_or(1) == 0);
    bool found = false;
    std::string why, names;
    sc.walls.for_each([&](auto& w, std::size_t) {
      names += (names.empty() ? "" : ", ") + w.name;
      if (w.name != name) return;
      found = true;
      if (w.control.active())
        why = "wall '" + name + "' is controlled (a servo or a strain rate): its control sets its velocity";
      else if (!moves && !still)
        why = "no wall of the case moves, so its step has no wall-motion stage (an absent effect runs no code); "
              "give a wall a motion in the case to change motions between stages";
      else if constexpr (requires { w.rebase(0.0, sim::Vec3{}, 0.0); }) {
        const sim::Vec3 offset = w.offset;  // the pose now, kept
        const double angle = w.angle;
        if (m.velocity) w.velocity = *m.velocity;
        if (m.angular_velocity) w.angular_velocity = *m.angular_velocity;
        if (m.vibration_amplitude) w.vibration_amplitude = *m.vibration_amplitude;
        if (m.vibration_frequency) w.vibration_frequency = *m.vibration_frequency;
        w.rebase(w.motion_time, offset, angle);
      } else if (m.angular_velocity || m.vibration_amplitude || m.vibration_frequency)
        why = "wall '" + name + "' is a " + std::string(std::decay_t<decltype(w)>::kind) +
              ": only its velocity can be set (rotation and vibration are a mesh wall's)";
      else if (m.velocity)
        w.velocity = *m.velocity;
    });
    if (!found) throw py::key_error("no wall '" + name + "' (the case has: " + names + ")");
    if (!why.empty()) throw py::value_error("set_wall_motion: " + why);
    rebuild();
  }

  // Steps to `target`, asking Python for a pending signal (Ctrl-C) now and then.
  std::int64_t advance_to(std::int64_t target) {
    before_change();
    py::scoped_estream_redirect to_python;  // progress lines to sys.stderr (a notebook shows them)
    bool interrupted = false;
    std::int64_t k = 0;
    auto stop = [&] {
      if (++k % 16 != 0) return false;
      if (PyErr_CheckSignals() != 0) interrupted = true;
      return interrupted;
    };
    const auto n = runner->advance(target, stop);
    if (interrupted) throw py::error_already_set();
    if (runner->signal() != 0) throw std::runtime_error("the run was interrupted by a signal");
    return n;
  }

  py::object close() {
    if (closed) return summary;
    validate_writes();
    detach_views();
    closed = true;
    py::scoped_estream_redirect to_python;
    const auto r = runner->finish();
    py::dict d;
    d["steps"] = r.steps;
    d["simulated_time"] = r.simulated_time;
    d["wall_seconds"] = r.wall_seconds;
    d["particle_steps_per_second"] = r.particle_steps_per_second;
    d["particles_start"] = r.particles_start;
    d["particles_end"] = r.particles_end;
    d["lost_particles"] = r.lost_particles;
    d["neighbor_builds"] = r.neighbor_builds;
    d["frames"] = r.frames;
    d["checkpoint"] = r.checkpoint;
    summary = d;
    return summary;
  }
};

sim::Vec3 vec3(const char* what, const std::vector<double>& v) {
  if (v.size() != 3) throw py::value_error(std::string(what) + ": three components");
  return {v[0], v[1], v[2]};
}

std::int64_t steps_for(const sim::Clock& c, double t) {
  if (!std::isfinite(t)) throw py::value_error("the time must be finite");
  return std::llround(t / c.dt);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "grains: discrete-element simulation of granular matter (compiled core; see docs/python.md)";
  m.attr("__version__") = std::string(kVersion);
  io::set_allocator_policy();  // large per-grain arrays straight from the kernel (io/run/allocator.hpp)

  // Errors carry the located messages the command line prints.
  static py::exception<io::CaseError> case_error(m, "CaseError", PyExc_ValueError);
  static py::exception<sim::SetupError> setup_error(m, "SetupError", PyExc_ValueError);
  static py::exception<io::CheckpointError> checkpoint_error(m, "CheckpointError", PyExc_OSError);
  static py::exception<io::BlowUp> blow_up(m, "BlowUpError", PyExc_ArithmeticError);
  static py::exception<io::OutputFailure> output_error(m, "OutputError", PyExc_OSError);
  static py::exception<sim::IntegrationFailure> integration_error(m, "IntegrationError", PyExc_ArithmeticError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::CaseError& e) {
      // The messages one by one: err.messages after `except grains.CaseError as err`.
      py::object err = py::handle(case_error.ptr())(e.what());
      err.attr("messages") = py::cast(e.messages);
      PyErr_SetObject(case_error.ptr(), err.ptr());
    } catch (const sim::SetupError& e) {
      setup_error(e.what());
    } catch (const io::CheckpointError& e) {
      checkpoint_error(e.what());
    } catch (const io::BlowUp& e) {
      blow_up(e.what());
    } catch (const io::OutputFailure& e) {
      output_error(e.what());
    } catch (const sim::IntegrationFailure& e) {
      integration_error(e.what());
    } catch (const std::logic_error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<ViewGuard>(m, "_ViewGuard");

  py::class_<PyCase>(m, "Case", R"(A case: a case file, YAML text or a dict, validated as `grains run` does.

Case(source, set=None, base_dir=None)
  source: a path to a case file (str or os.PathLike), or a dict with the
  case's sections. set: edits as {"time.end": 0.5} or ["time.end=0.5"].
  base_dir: where a dict's relative paths (meshes) start (default: the
  current folder). Problems raise grains.CaseError with every located
  message (err.messages).)")
      .def(py::init([](py::object source, py::object set, py::object base_dir) {
             std::vector<std::string> sets;
             std::vector<std::pair<std::string, py::object>> later;
             if (py::isinstance<py::dict>(set)) {
               for (auto kv : py::reinterpret_borrow<py::dict>(set))
                 later.emplace_back(kv.first.cast<std::string>(), py::reinterpret_borrow<py::object>(kv.second));
             } else if (!set.is_none()) {
               sets = set.cast<std::vector<std::string>>();
             }
             PyCase c;
             if (py::isinstance<py::dict>(source)) {
               const std::string dir = base_dir.is_none() ? std::string(".") : py::str(base_dir).cast<std::string>();
               c = PyCase::from_text(yaml_text(source, ""), "<dict>", dir, sets);
             } else if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
               const std::string path = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
               c = PyCase::from_file(path, sets);
             } else {
               throw py::type_error("Case(source): a path to a case file or a dict, not " +
                                    py::str(py::type::of(source).attr("__name__")).cast<std::string>());
             }
             for (auto& [k, v] : later) c.set(k, v);
             return c;
           }),
           py::arg("source"), py::arg("set") = py::none(), py::arg("base_dir") = py::none())
      .def_static("from_text", &PyCase::from_text, py::arg("text"), py::arg("name") = "<text>",
                  py::arg("base_dir") = ".", py::arg("set") = std::vector<std::string>{},
                  "A case from YAML text; `name` stands for the file in messages.")
      .def("set", [](PyCase& c, const std::string& key, py::object value) { c.set(key, value); }, py::arg("key"),
           py::arg("value"),
           "Sets a dotted key ('time.end', 'materials.0.friction') as `grains run --set` does; the case is "
           "validated again, and an edit that makes it invalid raises CaseError and is not kept.")
      .def("__setitem__", [](PyCase& c, const std::string& key, py::object value) { c.set(key, value); })
      .def("__getitem__", &PyCase::get)
      .def("get", [](const PyCase& c, const std::string& key, py::object dflt) -> py::object {
             try {
               return c.get(key);
             } catch (const py::key_error&) {
               return dflt;
             }
           }, py::arg("key"), py::arg("default") = py::none())
      .def("to_dict", [](const PyCase& c) { return yaml_to_py(c.c.root); }, "The case with its edits, as a dict.")
      .def_property_readonly("text", &PyCase::effective_text, "The case with its edits, as YAML.")
      .def_property_readonly("name", [](const PyCase& c) { return c.name; })
      .def_property_readonly("edits", [](const PyCase& c) { return c.overrides; })
      .def_property_readonly("end_time", [](const PyCase& c) { return c.c.scene.end_time; })
      .def("__repr__", [](const PyCase& c) {
        return "<grains.Case " + c.name + (c.overrides.empty() ? "" : " with " + std::to_string(c.overrides.size()) + " edit(s)") + ">";
      });

  py::class_<PySim>(m, "Simulation", R"(A simulation of a case, stepped from Python.

Simulation(case, out="out", restart=None, progress=None)
  case: a grains.Case (or what Case() takes). out: the output folder
  (frames, checkpoints, summary.json). restart: a checkpoint to continue
  from. progress: progress lines on stderr (default: when stderr is a
  terminal).)")
      .def(py::init([](py::object case_, py::object out, py::object restart, py::object progress) {
             PyCase c = py::isinstance<PyCase>(case_) ? case_.cast<PyCase>()
                                                       : py::module_::import("grains").attr("Case")(case_).cast<PyCase>();
             auto s = std::make_unique<PySim>();
             s->opt.out_dir = py::str(py::module_::import("os").attr("fspath")(out)).cast<std::string>();
             if (!restart.is_none())
               s->opt.restart = py::str(py::module_::import("os").attr("fspath")(restart)).cast<std::string>();
             bool show = false;
             if (progress.is_none()) {
               py::object err = py::module_::import("sys").attr("stderr");
               show = !err.is_none() && py::hasattr(err, "isatty") && err.attr("isatty")().cast<bool>();
             } else {
               show = progress.cast<bool>();
             }
             s->opt.quiet = !show;
             s->sim = std::make_unique<io::Simulation>(io::make_simulation(c.c));
             py::scoped_estream_redirect to_python;  // (the set-up's warnings)
             s->runner = std::make_unique<io::Runner>(*s->sim, s->opt);
             return s;
           }),
           py::arg("case"), py::arg("out") = "out", py::arg("restart") = py::none(), py::arg("progress") = py::none())
      .def("step", [](PySim& s, std::int64_t n) {
             if (n < 0) throw py::value_error("step(n): n must be >= 0");
             s.check_open();
             return s.advance_to(s.scene().clock.step + n);
           }, py::arg("n") = 1, "Takes n time steps; returns the steps taken.")
      .def("_advance_to", &PySim::advance_to, py::arg("step"))
      .def("_steps_for", [](PySim& s, double t) { s.check_open(); return steps_for(s.scene().clock, t); })
      .def("_remove", [](PySim& s, py::array_t<bool, py::array::c_style | py::array::forcecast> mask) {
             s.before_change();
             const auto n = static_cast<py::ssize_t>(s.scene().particles.n_owned());
             if (mask.ndim() != 1 || mask.shape(0) != n)
               throw py::value_error("remove: a mask of shape (" + std::to_string(n) + ",) (one flag per grain of "
                                     "this rank), got " + py::str(mask.attr("shape")).cast<std::string>());
             std::vector<char> flag(static_cast<std::size_t>(n));
             for (py::ssize_t i = 0; i < n; ++i) flag[static_cast<std::size_t>(i)] = mask.at(i) ? 1 : 0;
             return s.remove(flag);
           }, py::arg("mask"))
      .def("_insert", [](PySim& s, py::array_t<double, py::array::c_style | py::array::forcecast> x,
                         py::array_t<double, py::array::c_style | py::array::forcecast> r,
                         py::array_t<double, py::array::c_style | py::array::forcecast> v,
                         py::array_t<double, py::array::c_style | py::array::forcecast> q, std::size_t set) {
             s.before_change();
             const auto n = x.ndim() == 2 ? x.shape(0) : -1;
             if (n < 0 || x.shape(1) != 3) throw py::value_error("insert: positions of shape (k, 3)");
             if (r.ndim() != 1 || r.shape(0) != n) throw py::value_error("insert: radii of shape (k,)");
             if (v.ndim() != 2 || v.shape(0) != n || v.shape(1) != 3)
               throw py::value_error("insert: velocities of shape (k, 3)");
             if (q.ndim() != 2 || q.shape(0) != n || q.shape(1) != 4)
               throw py::value_error("insert: orientations of shape (k, 4), quaternions (x, y, z, w)");
             std::vector<sim::Vec3> xs, vs;
             std::vector<double> rs;
             std::vector<sim::Quat> qs;
             for (py::ssize_t k = 0; k < n; ++k) {
               const sim::Vec3 xk(x.at(k, 0), x.at(k, 1), x.at(k, 2)), vk(v.at(k, 0), v.at(k, 1), v.at(k, 2));
               sim::Quat qk(q.at(k, 3), q.at(k, 0), q.at(k, 1), q.at(k, 2));
               if (!xk.allFinite() || !vk.allFinite() || !std::isfinite(r.at(k)) || r.at(k) <= 0 ||
                   !qk.coeffs().allFinite() || qk.norm() == 0)
                 throw py::value_error("insert: row " + std::to_string(k) + " is not finite (or a radius <= 0, a "
                                       "zero quaternion); nothing was inserted");
               xs.push_back(xk);
               vs.push_back(vk);
               rs.push_back(r.at(k));
               qs.push_back(qk.normalized());
             }
             return s.insert(xs, rs, vs, qs, set);
           }, py::arg("positions"), py::arg("radii"), py::arg("velocities"), py::arg("orientations"), py::arg("set"))
      .def("set_material", [](PySim& s, const std::string& name, py::kwargs values) {
             s.before_change();
             s.set_material(name, values);
           }, py::arg("name"),
           "Changes a material's friction, rolling_friction, restitution or cohesion between steps, e.g. "
           "sim.set_material('glass', friction=0.3); the pair table is mixed again.")
      .def("set_wall_velocity", [](PySim& s, const std::string& name, const std::vector<double>& v) {
             s.before_change();
             PySim::WallMotion m;
             m.velocity = vec3("velocity", v);
             s.set_wall_motion(name, m);
           }, py::arg("name"), py::arg("velocity"),
           "Sets a wall's velocity (m/s) between steps, by the wall's name: set_wall_motion(name, velocity=v).")
      .def("set_wall_motion", [](PySim& s, const std::string& name, std::optional<std::vector<double>> v,
                                 std::optional<double> omega, std::optional<double> rpm,
                                 std::optional<std::vector<double>> amplitude, std::optional<double> frequency) {
             s.before_change();
             if (omega && rpm) throw py::value_error("set_wall_motion: give angular_velocity (rad/s) or rpm, not both");
             if (rpm) omega = *rpm * 2 * M_PI / 60;
             PySim::WallMotion m;
             m.angular_velocity = omega, m.vibration_frequency = frequency;
             if (v) m.velocity = vec3("velocity", *v);
             if (amplitude) m.vibration_amplitude = vec3("vibration_amplitude", *amplitude);
             s.set_wall_motion(name, m);
           }, py::arg("name"), py::kw_only(), py::arg("velocity") = py::none(),
           py::arg("angular_velocity") = py::none(), py::arg("rpm") = py::none(),
           py::arg("vibration_amplitude") = py::none(), py::arg("vibration_frequency") = py::none(),
           "Changes a wall's motion between steps. A plane or a cylinder: its velocity (m/s). A mesh wall: its "
           "velocity, its rotation speed about its axis (angular_velocity in rad/s, or rpm) and its vibration; it "
           "continues from its pose now (no jump), keeping its case's start and ramp. Values not given stay.")
      .def("checkpoint", [](PySim& s) {
             s.before_change();
             return s.runner->checkpoint().string();
           }, "Writes a checkpoint of this step into OUT/checkpoints; returns its path.")
      .def("close", &PySim::close,
           "Ends the run: the outputs' last records and summary.json; returns the summary as a dict. "
           "Stepping a closed simulation raises RuntimeError.")
      .def_property_readonly("closed", [](const PySim& s) { return s.closed; })
      .def_property_readonly("summary", [](const PySim& s) { return s.summary; })
      .def_property_readonly("time", [](PySim& s) { s.check_open(); return s.scene().clock.time; })
      .def_property_readonly("step_count", [](PySim& s) { s.check_open(); return s.scene().clock.step; })
      .def_property_readonly("dt", [](PySim& s) { s.check_open(); return s.scene().clock.dt; })
      .def_property_readonly("end_time", [](PySim& s) { s.check_open(); return s.scene().clock.end_time; })
      .def_property_readonly("out", [](const PySim& s) { return s.opt.out_dir.string(); })
      .def_property_readonly("warnings", [](const PySim& s) { return s.sim->c.scene.warnings; },
                             "What the set-up warned of (a time step close to the Rayleigh time, ...).")
      .def_property_readonly("n_particles", [](PySim& s) { s.check_open(); return s.scene().particles.n_owned(); },
                             "The grains this rank owns (all of them when serial).")
      .def_property_readonly("n_total", [](PySim& s) {
        s.check_open();
        return sim::Comm::world().sum(static_cast<std::int64_t>(s.scene().particles.n_owned()));
      }, "The grains of all ranks (under MPI every rank must ask: it is a collective sum).")
      .def_property("gravity",
                    [](PySim& s) {
                      s.check_open();
                      const auto& g = s.scene().gravity;
                      return py::make_tuple(g.x(), g.y(), g.z());
                    },
                    [](PySim& s, std::vector<double> g) {
                      s.check_open();
                      if (g.size() != 3) throw py::value_error("gravity: three components (m/s^2)");
                      for (double x : g)
                        if (!std::isfinite(x)) throw py::value_error("gravity: the components must be finite");
                      if (s.scene().gravity.isZero(0))
                        throw py::value_error("gravity: the case has none, so its step has no gravity stage (an "
                                              "absent effect runs no code); give gravity in the case (a small "
                                              "value will do) to change it between stages");
                      s.scene().gravity = sim::Vec3(g[0], g[1], g[2]);
                    },
                    "Gravity (m/s^2) as a tuple; settable between steps when the case has gravity.")
      .def("field", [](py::object self, const std::string& name, bool writable) {
             return self.cast<PySim&>().view(self, name, writable);
           }, py::arg("name"), py::arg("writable") = true,
           "A numpy view of a per-particle field of this rank's grains (no copy); see docs/python.md.")
      .def("set_field", [](py::object self, const std::string& name, py::object values) {
             self.cast<PySim&>().write(name, values);
           }, py::arg("name"), py::arg("values"),
           "Writes a field from an array, checked (dtype, shape, finite, inside the domain) before anything is "
           "written.")
      .def_property_readonly("field_names", [](PySim& s) {
        s.check_open();
        std::vector<std::string> names;
        for (const auto& f : field_refs())
          if (f.size(s.scene().particles) > 0) names.push_back(f.name);
        return names;
      })
      .def("_address", [](PySim& s, const std::string& name) {
        s.check_open();
        return reinterpret_cast<std::uintptr_t>(field_ref(name).data(s.scene().particles));
      })
      .def("describe", [](PySim& s) { s.check_open(); return io::describe(*s.sim); });

  // Under mpirun (`mpirun -np N python3 script.py`) MPI starts with the
  // module, unless mpi4py started it already; grains then ends it at exit.
  sim::Comm::init(nullptr, nullptr, false);
  py::module_::import("atexit").attr("register")(py::cpp_function([] { sim::Comm::finalize(); }));
  m.def("mpi_rank", [] { return sim::Comm::world().rank(); }, "This process's MPI rank (0 when serial).");
  m.def("mpi_size", [] { return sim::Comm::world().size(); }, "The number of MPI ranks (1 when serial).");

  m.def("_analyze", [](const std::string& dir, long frame, py::object time, py::object region) {
    namespace pp = postprocess;
    pp::Frame f = time.is_none() ? pp::read_frame(dir, frame) : pp::read_frame_at_time(dir, time.cast<double>());
    pp::AnalysisOptions opt;
    if (!region.is_none()) {
      const auto c = region.cast<std::vector<std::vector<double>>>();
      if (c.size() != 2 || c[0].size() != 3 || c[1].size() != 3)
        throw py::value_error("analyze: region = ((xmin, ymin, zmin), (xmax, ymax, zmax))");
      opt.region = pp::Box{sim::Vec3(c[0][0], c[0][1], c[0][2]), sim::Vec3(c[1][0], c[1][1], c[1][2])};
    }
    std::optional<pp::WallSet> walls;
    if (const auto wf = pp::walls_file(dir, f.index); !wf.empty() && opt.wall_contacts) walls = pp::read_walls(wf);
    const auto r = pp::analyze_frame(f, opt, walls ? &*walls : nullptr);
    py::dict d = py::module_::import("json").attr("loads")(pp::analysis_json(r));
    py::dict prof;
    prof["axis"] = r.profile.axis;
    prof["lo"] = py::array(py::cast(r.profile.lo));
    prof["hi"] = py::array(py::cast(r.profile.hi));
    prof["phi"] = py::array(py::cast(r.profile.phi));
    prof["error"] = py::array(py::cast(r.profile.error));
    d["phi_profile"] = prof;
    if (r.rdf) {
      py::dict g;
      g["r"] = py::array(py::cast(r.rdf->r));
      g["g"] = py::array(py::cast(r.rdf->g));
      d["rdf_arrays"] = g;
    }
    d["coordination_histogram"] = py::array(py::cast(r.coordination.histogram));
    return d;
  }, py::arg("out_dir"), py::arg("frame") = -1, py::arg("time") = py::none(), py::arg("region") = py::none());

  m.def("omp_threads", [] { return omp_get_max_threads(); }, "OpenMP threads a step uses (OMP_NUM_THREADS).");
}
