// tspplay._core.build_series / build_input: a .tsp file from numpy arrays, an iterator of steps,
// or any input the CLI's `build` reads, through tsp::build_tsp_file as `build` does.
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "py_common.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/source/volume_source.h"
#include "tsp/voxelize/open_input.h"

namespace tsppy {
namespace {

// One 3-D step as the builder reads it: a pointer, byte strides and the element type. The
// array (owned by the source) keeps the memory alive; reading it needs no GIL.
struct StepView {
  const char* data = nullptr;
  std::array<py::ssize_t, 3> strides{};  // bytes, (z, y, x)
  char kind = 'f';                       // numpy kind: f, i, u, b
  int itemsize = 4;
};

// The value of element (z, y, x) of v as a float.
float element(const StepView& v, std::int64_t z, std::int64_t y, std::int64_t x) {
  const char* p = v.data + z * v.strides[0] + y * v.strides[1] + x * v.strides[2];
  switch (v.kind) {
    case 'f':
      if (v.itemsize == 4) return *reinterpret_cast<const float*>(p);
      if (v.itemsize == 8) return float(*reinterpret_cast<const double*>(p));
      break;
    case 'i':
      if (v.itemsize == 1) return float(*reinterpret_cast<const std::int8_t*>(p));
      if (v.itemsize == 2) return float(*reinterpret_cast<const std::int16_t*>(p));
      if (v.itemsize == 4) return float(*reinterpret_cast<const std::int32_t*>(p));
      if (v.itemsize == 8) return float(*reinterpret_cast<const std::int64_t*>(p));
      break;
    case 'u':
    case 'b':
      if (v.itemsize == 1) return float(*reinterpret_cast<const std::uint8_t*>(p));
      if (v.itemsize == 2) return float(*reinterpret_cast<const std::uint16_t*>(p));
      if (v.itemsize == 4) return float(*reinterpret_cast<const std::uint32_t*>(p));
      if (v.itemsize == 8) return float(*reinterpret_cast<const std::uint64_t*>(p));
      break;
  }
  return 0;
}

// Planes z0..z1-1 of v (dims d) into out: one copy for C-contiguous float32, else element-wise.
void copy_planes(const StepView& v, tsp::Dims d, int z0, int z1, std::span<float> out) {
  const std::int64_t plane = std::int64_t(d.x) * d.y;
  const bool packed = v.kind == 'f' && v.itemsize == 4 && v.strides[2] == 4 &&
                      v.strides[1] == 4 * py::ssize_t(d.x) && v.strides[0] == 4 * plane;
  if (packed) {
    std::memcpy(out.data(), v.data + z0 * v.strides[0], std::size_t((z1 - z0) * plane) * 4);
    return;
  }
  float* o = out.data();
  for (std::int64_t z = z0; z < z1; ++z)
    for (std::int64_t y = 0; y < d.y; ++y)
      for (std::int64_t x = 0; x < d.x; ++x) *o++ = element(v, z, y, x);
}

// The 3-D array a as a StepView; throws tsp::UsageError naming what for another rank or type.
StepView step_view(const py::array& a, const std::string& what) {
  if (a.ndim() != 3)
    throw tsp::UsageError(what + ": expected a 3-D array (z, y, x), got " +
                          std::to_string(a.ndim()) + "-D");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw tsp::UsageError(what + ": expected numbers (float, int or uint), got dtype " +
                          std::string(py::str(a.dtype())));
  if (kind == 'f' && a.itemsize() != 4 && a.itemsize() != 8)
    throw tsp::UsageError(what + ": expected float32 or float64, got dtype " +
                          std::string(py::str(a.dtype())));
  StepView v;
  v.data = static_cast<const char*>(a.data());
  v.strides = {a.strides(0), a.strides(1), a.strides(2)};
  v.kind = kind;
  v.itemsize = int(a.itemsize());
  return v;
}

// Throws tsp::FormatError at the first non-finite sample of out (step t), when refused.
void check_finite(std::span<const float> out, int t, tsp::Dims d, int z0) {
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i])) {
      const std::int64_t plane = std::int64_t(d.x) * d.y, k = std::int64_t(i);
      throw tsp::FormatError("step " + std::to_string(t) + ": sample (z, y, x) = (" +
                             std::to_string(z0 + k / plane) + ", " +
                             std::to_string(k % plane / d.x) + ", " + std::to_string(k % d.x) +
                             ") is " + (std::isnan(out[i]) ? "NaN" : "infinite") +
                             " (nonfinite='replace' replaces such samples as `tspplay build` does)");
    }
}

// Planes per slab an array hands the builder: the builder's own choice (a quarter of a brick
// layer) took 8x more passes of its slab loop than an HDF5 input chunked 64 planes deep and built
// ~15 % slower (docs/results.md); 64 planes cost at most 64 planes of buffer.
constexpr int kSlabPlanes = 64;

// What every in-memory source reports besides the samples.
struct SeriesInfo {
  std::vector<double> times;
  tsp::TimeUnits units;
  std::string name;
  bool refuse_nonfinite = false;
};

// A series of numpy arrays (3-D steps, each possibly a view into one 4-D array), read without a
// copy of the series: each step or slab is copied (or converted) straight into the builder's
// buffer. Thread-safe reads; the GIL is needed only to make and destroy it.
class ArraySource final : public tsp::VolumeSource {
 public:
  ArraySource(const py::list& steps, SeriesInfo info) : info_(std::move(info)) {
    if (steps.empty()) throw tsp::UsageError("build: the series has no steps");
    for (std::size_t t = 0; t < steps.size(); ++t) {
      py::array a = py::array::ensure(steps[t]);
      if (!a) throw tsp::UsageError("build: step " + std::to_string(t) + " is not an array");
      views_.push_back(step_view(a, "build: step " + std::to_string(t)));
      const tsp::Dims d{int(a.shape(2)), int(a.shape(1)), int(a.shape(0))};
      if (t == 0) dims_ = d;
      if (!(d == dims_))
        throw tsp::UsageError("build: step " + std::to_string(t) + " has shape (" +
                              std::to_string(d.z) + ", " + std::to_string(d.y) + ", " +
                              std::to_string(d.x) + "), step 0 (" + std::to_string(dims_.z) +
                              ", " + std::to_string(dims_.y) + ", " + std::to_string(dims_.x) + ")");
      arrays_.push_back(std::move(a));
    }
    if (dims_.count() == 0) throw tsp::UsageError("build: the steps are empty arrays");
  }
  tsp::Dims dims() const override { return dims_; }
  int steps() const override { return int(views_.size()); }
  std::string describe() const override { return info_.name; }
  void read_step(int t, std::span<float> out) override { read_slab(t, 0, dims_.z, out); }
  bool reads_slabs() const override { return true; }
  int slab_alignment() const override { return kSlabPlanes; }
  void read_slab(int t, int z0, int z1, std::span<float> out) override {
    copy_planes(views_[std::size_t(t)], dims_, z0, z1, out);
    if (info_.refuse_nonfinite) check_finite(out, t, dims_, z0);
  }
  std::vector<double> times() const override { return info_.times; }
  tsp::TimeUnits time_units() const override { return info_.units; }

 private:
  SeriesInfo info_;
  std::vector<py::array> arrays_;  // destroyed with the GIL held (by the binding)
  std::vector<StepView> views_;
  tsp::Dims dims_;
};

// Steps from a Python iterator, read once and in order (a series larger than RAM: one step in
// memory at a time). Each read takes the GIL to call next().
class IteratorSource final : public tsp::VolumeSource {
 public:
  IteratorSource(py::iterator it, int steps, SeriesInfo info)
      : it_(std::move(it)), steps_(steps), info_(std::move(info)) {
    if (steps < 1) throw tsp::UsageError("build: an iterator needs steps=N (N >= 1), its length");
    first_ = next_array(0);
    const py::array& a = *first_;
    dims_ = {int(a.shape(2)), int(a.shape(1)), int(a.shape(0))};
    if (dims_.count() == 0) throw tsp::UsageError("build: step 0 is an empty array");
  }
  ~IteratorSource() override {
    py::gil_scoped_acquire gil;
    first_.reset();
    it_ = py::iterator();
  }
  tsp::Dims dims() const override { return dims_; }
  int steps() const override { return steps_; }
  std::string describe() const override { return info_.name; }
  void read_step(int t, std::span<float> out) override {
    py::gil_scoped_acquire gil;
    if (t != next_)
      throw tsp::UsageError("build: an iterator is read once, in order; step " +
                            std::to_string(t) + " was asked for after step " +
                            std::to_string(next_ - 1));
    py::array a = first_ ? std::move(*first_) : next_array(t);
    first_.reset();
    const StepView v = step_view(a, "build: step " + std::to_string(t));
    const tsp::Dims d{int(a.shape(2)), int(a.shape(1)), int(a.shape(0))};
    if (!(d == dims_))
      throw tsp::UsageError("build: step " + std::to_string(t) + " has another shape than step 0");
    {
      py::gil_scoped_release release;  // the copy itself needs no GIL
      copy_planes(v, dims_, 0, dims_.z, out);
      if (info_.refuse_nonfinite) check_finite(out, t, dims_, 0);
    }
    ++next_;
  }
  std::vector<double> times() const override { return info_.times; }
  tsp::TimeUnits time_units() const override { return info_.units; }

 private:
  // The iterator's next item as an array (GIL held).
  py::array next_array(int t) {
    py::object item = py::reinterpret_steal<py::object>(PyIter_Next(it_.ptr()));
    if (!item) {
      if (PyErr_Occurred()) throw py::error_already_set();
      throw tsp::UsageError("build: the iterator ended after " + std::to_string(t) +
                            " steps; steps=" + std::to_string(steps_) + " were announced");
    }
    py::array a = py::array::ensure(item);
    if (!a) throw tsp::UsageError("build: step " + std::to_string(t) + " is not an array");
    step_view(a, "build: step " + std::to_string(t));
    return a;
  }

  py::iterator it_;
  int steps_;
  SeriesInfo info_;
  std::optional<py::array> first_;  // step 0, read to learn the grid
  tsp::Dims dims_;
  int next_ = 0;
};

// The build options from the binding's arguments (checks left to the builder, as for the CLI).
tsp::BuildOptions build_options(const std::string& field, int brick, const py::object& range,
                                const py::object& spacing, const py::object& origin, int deflate,
                                int threads) {
  tsp::BuildOptions bo;
  bo.field_name = field;
  bo.brick_size = brick;
  bo.threads = threads;
  bo.deflate = deflate;
  if (!range.is_none()) {
    const auto r = range.cast<std::array<double, 2>>();
    bo.range = tsp::ValueRange{r[0], r[1]};
  }
  if (!spacing.is_none()) bo.spacing = spacing.cast<std::array<double, 3>>();
  if (!origin.is_none()) bo.origin = origin.cast<std::array<double, 3>>();
  return bo;
}

py::dict report_dict(const tsp::BuildReport& r) {
  py::dict d;
  d["source_bytes"] = r.source_bytes;
  d["nonfinite_count"] = r.nonfinite_count;
  d["seconds"] = r.seconds;
  d["data_range"] = py::make_tuple(r.data_range.lo, r.data_range.hi);
  d["value_range"] = py::make_tuple(r.value_range.lo, r.value_range.hi);
  return d;
}

// Builds out from source with GIL released, progress relayed and Ctrl-C honoured.
py::dict run_build(tsp::VolumeSource& source, const std::string& out, tsp::BuildOptions bo,
                   const py::object& progress) {
  if (bo.brick_size == 0) bo.brick_size = tsp::default_brick_size(source.dims());
  bo.progress = progress_relay(progress);
  tsp::BuildReport r;
  {
    py::gil_scoped_release release;
    r = tsp::build_tsp_file(source, out, bo);
  }
  return report_dict(r);
}

}  // namespace

void bind_build(py::module_& m) {
  m.def(
      "build_series",
      [](py::object steps, const std::string& out, int count, const std::string& field, int brick,
         py::object range, py::object spacing, py::object origin, std::vector<double> times,
         const std::string& time_units, const std::string& calendar, int deflate, int threads,
         bool refuse_nonfinite, const std::string& name, py::object progress) {
        SeriesInfo info{std::move(times), {time_units, calendar}, name, refuse_nonfinite};
        const tsp::BuildOptions bo =
            build_options(field, brick, range, spacing, origin, deflate, threads);
        if (py::isinstance<py::list>(steps)) {
          ArraySource source(steps.cast<py::list>(), std::move(info));
          return run_build(source, out, bo, progress);
        }
        IteratorSource source(py::iter(steps), count, std::move(info));
        return run_build(source, out, bo, progress);
      },
      py::arg("steps"), py::arg("out"), py::arg("count") = 0, py::arg("field") = "",
      py::arg("brick") = 0, py::arg("range") = py::none(), py::arg("spacing") = py::none(),
      py::arg("origin") = py::none(), py::arg("times") = std::vector<double>{},
      py::arg("time_units") = "", py::arg("calendar") = "", py::arg("deflate") = 0,
      py::arg("threads") = 0, py::arg("refuse_nonfinite") = false,
      py::arg("name") = "numpy array", py::arg("progress") = py::none(),
      "Builds out (a .tsp file) from a list of 3-D arrays (z, y, x) or an iterator of count of "
      "them; the build of `tspplay build`. Raises UsageError, FormatError, IoError, "
      "KeyboardInterrupt (nothing written).");
  m.def(
      "build_input",
      [](const std::string& input, const std::string& out, const std::string& field, int brick,
         py::object range, py::object spacing, py::object origin, int deflate, int threads,
         py::object progress) {
        tsp::SourceOptions so;
        so.field = field;
        tsp::BuildOptions bo = build_options(field, brick, range, spacing, origin, deflate, threads);
        std::unique_ptr<tsp::VolumeSource> source;
        {
          py::gil_scoped_release release;
          source = tsp::open_input(input, so, tsp::VoxelizeOptions{});
        }
        return run_build(*source, out, bo, progress);
      },
      py::arg("input"), py::arg("out"), py::arg("field") = "", py::arg("brick") = 0,
      py::arg("range") = py::none(), py::arg("spacing") = py::none(),
      py::arg("origin") = py::none(), py::arg("deflate") = 0, py::arg("threads") = 0,
      py::arg("progress") = py::none(),
      "Builds out from any input `tspplay build` reads (HDF5, NetCDF, VTK, raw, meshes). Raises "
      "like build_series.");
}

}  // namespace tsppy
