// The Python module `contour4d` (pybind11): a thin layer over the library's runs (pipeline/), so a script
// gets what the command line writes, as numpy arrays and dicts. Options are keyword arguments with the
// command line's names (dashes as underscores) and defaults; the work runs without the GIL; errors are
// Python exceptions carrying the command line's exit code. Reference: docs/python.md.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/metrics/evaluation.h"
#include "contour4d/pipeline/pack_run.h"
#include "contour4d/pipeline/reconstruct_run.h"
#include "contour4d/temporal/sequence.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace c4d::python {
namespace {

// ---- exceptions: one Python class per C++ class, each instance carrying exit_code and hint ----------------

struct ExceptionClasses {
  py::object error, io_error, invalid_input, solver_error;
};

ExceptionClasses& exception_classes() {
  static ExceptionClasses classes;
  return classes;
}

py::object new_exception(py::module_& m, const char* name, const py::object& base, const char* doc) {
  const std::string qualified = std::string("contour4d.") + name;
  py::object cls =
      py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base.ptr(), nullptr));
  m.attr(name) = cls;
  return cls;
}

void register_exceptions(py::module_& m) {
  ExceptionClasses& c = exception_classes();
  c.error =
      new_exception(m, "Error", py::reinterpret_borrow<py::object>(PyExc_RuntimeError),
                    "A contour4d failure: .exit_code is the command line's exit code (docs/cli.md), .hint what to do.");
  c.io_error = new_exception(m, "IoError", c.error, "A file could not be read or written.");
  c.invalid_input =
      new_exception(m, "InvalidInput", c.error, "The input violates the model (values, geometry, structure).");
  c.solver_error = new_exception(m, "SolverError", c.error,
                                 "A numerical stage failed, or the result failed its checks (exit_code 26).");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      const ExceptionClasses& classes = exception_classes();
      const py::object& cls = dynamic_cast<const IoError*>(&e)        ? classes.io_error
                              : dynamic_cast<const InvalidInput*>(&e) ? classes.invalid_input
                              : dynamic_cast<const SolverError*>(&e)  ? classes.solver_error
                                                                      : classes.error;
      py::object instance = cls(e.what());
      instance.attr("exit_code") = static_cast<int>(e.code());
      instance.attr("hint") = e.hint();
      instance.attr("message") = std::string(e.what());
      PyErr_SetObject(cls.ptr(), instance.ptr());
    }
  });
}

// ---- numpy <-> plain data -----------------------------------------------------------------------------------

py::array_t<double> points_array(const std::vector<Vec3>& points) {
  py::array_t<double> a({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  if (!points.empty()) std::memcpy(a.mutable_data(), points.data(), points.size() * sizeof(Vec3));
  return a;
}

std::vector<Vec3> points_from(const py::handle& h, const std::string& where) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  if (!a || a.ndim() != 2 || a.shape(1) != 3)
    throw InvalidInput(ErrorCode::Parse, Location{where}, "\"points\" must be an array of shape (n, 3) in mm");
  std::vector<Vec3> points;
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) points.push_back({v(i, 0), v(i, 1), v(i, 2)});
  return points;
}

// A mesh sequence as {"positions": (F, V, 3), "triangles": (T, 3), "times_ms": (F,)}.
py::dict mesh_dict(const MeshSequence& seq) {
  const auto nf = static_cast<py::ssize_t>(seq.positions.size());
  const auto nv = static_cast<py::ssize_t>(seq.positions.empty() ? 0 : seq.positions.front().size());
  py::array_t<double> positions({nf, nv, py::ssize_t{3}});
  for (py::ssize_t f = 0; f < nf; ++f)
    std::memcpy(positions.mutable_data(f), seq.positions[static_cast<std::size_t>(f)].data(),
                static_cast<std::size_t>(nv) * sizeof(Vec3));
  py::array_t<std::int64_t> triangles({static_cast<py::ssize_t>(seq.triangles.size()), py::ssize_t{3}});
  auto t = triangles.mutable_unchecked<2>();
  for (std::size_t i = 0; i < seq.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) t(static_cast<py::ssize_t>(i), k) = seq.triangles[i][static_cast<std::size_t>(k)];
  return py::dict("positions"_a = positions, "triangles"_a = triangles,
                  "times_ms"_a = py::array(py::cast(seq.times_ms)));
}

MeshSequence mesh_from(const py::dict& d) {
  const auto pos = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d["positions"]);
  const auto tri = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(d["triangles"]);
  if (!pos || pos.ndim() != 3 || pos.shape(2) != 3 || !tri || tri.ndim() != 2 || tri.shape(1) != 3)
    throw InvalidInput(ErrorCode::BadMesh, Location{"mesh"},
                       "a mesh is {\"positions\": (frames, vertices, 3), \"triangles\": (n, 3)[, \"times_ms\"]}");
  MeshSequence seq;
  const auto v = pos.unchecked<3>();
  for (py::ssize_t f = 0; f < pos.shape(0); ++f) {
    std::vector<Vec3> p;
    for (py::ssize_t i = 0; i < pos.shape(1); ++i) p.push_back({v(f, i, 0), v(f, i, 1), v(f, i, 2)});
    seq.positions.push_back(std::move(p));
  }
  const auto t = tri.unchecked<2>();
  for (py::ssize_t i = 0; i < tri.shape(0); ++i) {
    Triangle tr{};
    for (int k = 0; k < 3; ++k) {
      if (t(i, k) < 0 || t(i, k) >= pos.shape(1))
        throw InvalidInput(ErrorCode::BadMesh, Location{"mesh"},
                           "triangle " + std::to_string(i) + " indexes no vertex");
      tr[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(t(i, k));
    }
    seq.triangles.push_back(tr);
  }
  if (d.contains("times_ms"))
    seq.times_ms = d["times_ms"].cast<std::vector<double>>();
  else
    for (std::size_t f = 0; f < seq.positions.size(); ++f) seq.times_ms.push_back(static_cast<double>(f));
  return seq;
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

// ---- input ----------------------------------------------------------------------------------------------------

InputOptions input_options(const py::kwargs& kw) {
  InputOptions o;
  for (auto item : kw) {
    const std::string k = py::str(item.first);
    const py::handle v = item.second;
    if (k == "type")
      o.contour_types = py::isinstance<py::str>(v) ? std::vector<std::string>{v.cast<std::string>()}
                                                   : v.cast<std::vector<std::string>>();
    else if (k == "label")
      o.label = v.cast<std::string>();
    else if (k == "labels")
      o.label_preset = v.cast<std::string>();
    else if (k == "slice_axis")
      o.slice_axis = v.cast<int>();
    else if (k == "space")
      o.space = v.cast<std::string>();
    else if (k == "frame_ms")
      o.frame_ms = v.cast<double>();
    else if (k == "cycle_ms")
      o.cycle_ms = v.cast<double>();
    else if (k == "strict")
      o.strict = v.cast<bool>();
    else if (k == "align_slices")
      o.align_slices = v.cast<bool>();
    else if (k == "exact_contours")
      o.contour_tolerance_mm = v.cast<bool>() ? 0.0 : o.contour_tolerance_mm;
    else if (k == "contour_tolerance")
      o.contour_tolerance_mm = v.cast<double>();
    else
      throw InvalidInput(ErrorCode::Usage, Location{}, "unknown option " + k + "=");
  }
  return o;
}

// Contours given in memory: a list of {"frame", "slice", "points" (n, 3)[, "label"][, "time_ms"]}.
InputResult read_list(const py::list& contours, const InputOptions& options) {
  std::vector<RawContour> raw;
  std::vector<double> times;
  int frames = 0;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const py::dict c = contours[i].cast<py::dict>();
    const std::string where = "contours[" + std::to_string(i) + "]";
    RawContour r;
    r.frame = c.contains("frame") ? c["frame"].cast<int>() : 0;
    if (r.frame < 0) throw InvalidInput(ErrorCode::Parse, Location{where}, "\"frame\" must be 0 or more");
    r.contour.slice = c.contains("slice") ? c["slice"].cast<int>() : 0;
    r.contour.label = c.contains("label") ? c["label"].cast<std::string>() : std::string();
    if (!c.contains("points")) throw InvalidInput(ErrorCode::Parse, Location{where}, "no \"points\"");
    r.contour.points = points_from(c["points"], where);
    r.index = static_cast<int>(i);
    frames = std::max(frames, r.frame + 1);
    if (c.contains("time_ms")) {
      if (times.size() < static_cast<std::size_t>(frames)) times.resize(static_cast<std::size_t>(frames), -1.0);
      times[static_cast<std::size_t>(r.frame)] = c["time_ms"].cast<double>();
    }
    raw.push_back(std::move(r));
  }
  if (!times.empty() &&
      (times.size() != static_cast<std::size_t>(frames) || std::find(times.begin(), times.end(), -1.0) != times.end()))
    throw InvalidInput(ErrorCode::Parse, Location{"contours"}, "give \"time_ms\" on every contour or on none");
  py::gil_scoped_release release;
  return read_contour_list(std::move(raw), frames, times, "contours", options);
}

// INPUT as a path, a list of contour dicts, or the dict read() returns.
InputResult read_input(const py::object& input, const InputOptions& options, std::string& name) {
  if (py::isinstance<py::dict>(input)) return read_input(py::object(input.cast<py::dict>()["contours"]), options, name);
  if (py::isinstance<py::list>(input)) {
    name = "contours";
    return read_list(input.cast<py::list>(), options);
  }
  const std::filesystem::path path = input.cast<std::filesystem::path>();
  name = path.string();
  py::gil_scoped_release release;
  return read_contours(path, options);
}

py::dict input_dict(const InputResult& r) {
  py::list contours, repairs;
  for (std::size_t f = 0; f < r.sequence.frames.size(); ++f)
    for (const Slice& s : r.sequence.frames[f].slices)
      for (const Contour& c : s.contours)
        contours.append(py::dict("frame"_a = f, "slice"_a = s.id, "label"_a = c.label, "offset_mm"_a = s.offset,
                                 "time_ms"_a = r.sequence.frames[f].time_ms, "points"_a = points_array(c.points)));
  for (const ContourRepair& p : r.repairs)
    repairs.append(py::dict("frame"_a = p.frame, "slice"_a = p.slice, "contour"_a = p.contour, "kind"_a = p.kind,
                            "detail"_a = p.detail, "moved_mm"_a = p.moved_mm));
  const Vec3 n = r.sequence.normal;
  return py::dict("format"_a = r.format, "space"_a = r.sequence.space, "units"_a = r.sequence.units,
                  "stack_normal"_a = py::make_tuple(n.x, n.y, n.z), "frames"_a = r.sequence.frames.size(),
                  "timing"_a = r.timing, "notes"_a = r.notes, "repairs"_a = repairs, "contours"_a = contours);
}

py::dict read_to_dict(const py::object& input, const py::kwargs& kw) {
  std::string name;
  return input_dict(read_input(input, input_options(kw), name));
}

// ---- reconstruct ----------------------------------------------------------------------------------------------

// Splits keyword arguments into the run's options and the input's.
ReconstructRunOptions run_options(py::kwargs& kw) {
  ReconstructRunOptions o;
  auto take = [&kw](const char* key, auto& field) {
    if (!kw.contains(key)) return;
    field = kw[key].cast<std::remove_reference_t<decltype(field)>>();
    PyDict_DelItemString(kw.ptr(), key);
  };
  take("frame", o.frame);
  take("edge", o.edge);
  take("cap", o.cap);
  take("method", o.method);
  take("threads", o.threads);
  take("vertical_deformation", o.vertical);
  take("tiling", o.tiling);
  take("volume_tolerance", o.volume_tolerance);
  return o;
}

py::dict reconstruct(const py::object& input, const std::optional<std::filesystem::path>& output,
                     const std::optional<std::filesystem::path>& keep_failed, const std::string& format,
                     py::kwargs kw) {
  ReconstructRunOptions options = run_options(kw);
  const InputOptions in = input_options(kw);
  options.label = in.label;
  std::string name;
  const InputResult read = read_input(input, in, name);
  ReconstructRun run;
  {
    py::gil_scoped_release release;
    const MeshFormats formats = parse_mesh_formats(format);
    std::optional<OutputDir> out;
    if (output) out.emplace(*output);
    run = reconstruct_run(read, name, options);
    if (out)
      write_run(*out, run, formats, keep_failed ? keep_failed->string() : std::string());
    else
      throw_if_failed(run, "pass output= and keep_failed= to write the failed result for debugging");
  }
  py::dict d = mesh_dict(run.result);
  d["report"] = json_loads(run.report);
  return d;
}

// ---- evaluate, load, pack, unpack -----------------------------------------------------------------------------

py::dict evaluate_folder(const std::filesystem::path& outdir, const std::optional<std::filesystem::path>& contours,
                         const std::optional<std::filesystem::path>& truth, const std::string& label,
                         const std::vector<std::string>& type, double step, double sample_spacing,
                         bool self_intersections, const std::optional<std::filesystem::path>& json) {
  std::string text;
  {
    py::gil_scoped_release release;
    const MeshFrames meshes = read_mesh_frames(outdir);
    if (meshes.meshes.empty())
      throw IoError(ErrorCode::BadMesh, {outdir.string()}, "no mesh frames found",
                    "pass the folder written by reconstruct (it holds mesh.pvd and frames/)");
    std::optional<Sequence> seq;
    if (contours) {
      InputOptions in;
      in.label = label;
      in.contour_types = type;
      seq = read_contours(*contours, in).sequence;
    }
    std::optional<MeshFrames> truth_frames;
    if (truth) truth_frames = read_mesh_frames(*truth);
    EvaluationOptions opt;
    opt.conformity.step = step;
    opt.sampling.spacing = sample_spacing;
    opt.topology.self_intersections = self_intersections;
    text =
        format_evaluation_json(evaluate(meshes, seq ? &*seq : nullptr, truth_frames ? &*truth_frames : nullptr, opt));
    if (json) write_file_atomic(*json, text);
  }
  return json_loads(text);
}

py::dict load(const std::filesystem::path& path) {
  MeshSequence seq;
  {
    py::gil_scoped_release release;
    seq = load_mesh_sequence(path);
  }
  return mesh_dict(seq);
}

py::dict pack(const py::object& input, const std::optional<std::filesystem::path>& output, double tolerance,
              double normal_p99, double step, std::size_t resample, const std::string& interp, bool gltf,
              bool gltf_step, bool gltf_quantized) {
  PackRunOptions o;
  o.tolerance = tolerance;
  o.step = step;
  o.normal_p99 = normal_p99;
  o.resample = resample;
  o.interp = interp;
  o.gltf = gltf;
  o.gltf_step = gltf_step;
  o.gltf_quantized = gltf_quantized;
  const bool is_path = !py::isinstance<py::dict>(input);
  const MeshSequence given = is_path ? MeshSequence{} : mesh_from(input.cast<py::dict>());
  const std::filesystem::path path = is_path ? input.cast<std::filesystem::path>() : std::filesystem::path();
  PackRun run;
  std::filesystem::path out;
  {
    py::gil_scoped_release release;
    run = pack_run(is_path ? load_mesh_sequence(path) : given, o);
    if (output)
      out = *output;
    else if (is_path)
      out = (std::filesystem::is_directory(path) ? path : path.parent_path()) / "model.c4d";
    if (!out.empty()) {
      write_file_atomic(out, run.c4d);
      if (!run.glb.empty()) write_file_atomic(std::filesystem::path(out).replace_extension(".glb"), run.glb);
    }
  }
  const CompactStats& st = run.stats;
  return py::dict("path"_a = out.empty() ? py::object(py::none()) : py::str(out.string()),
                  "model"_a = py::bytes(run.c4d), "bytes"_a = run.c4d.size(), "glb_bytes"_a = run.glb.size(),
                  "payload_bytes_before_compression"_a = run.raw_payload, "payload_bytes_stored"_a = run.stored_payload,
                  "max_error_mm"_a = st.max_error, "rms_error_mm"_a = st.rms_error, "bound_mm"_a = run.model.tolerance,
                  "step_mm"_a = run.model.step, "normal_p99_deg"_a = st.normal_p99, "normal_max_deg"_a = st.normal_max);
}

py::dict unpack(const py::object& model, const std::optional<std::filesystem::path>& output, std::size_t resample,
                const std::string& interp, const std::string& format) {
  const bool is_bytes = py::isinstance<py::bytes>(model);
  const std::string bytes = is_bytes ? model.cast<std::string>() : std::string();
  const std::filesystem::path path =
      is_bytes ? std::filesystem::path("model.c4d") : model.cast<std::filesystem::path>();
  MeshSequence seq;
  {
    py::gil_scoped_release release;
    const CompactModel m = is_bytes ? parse_model_c4d(bytes, "model.c4d") : read_model_c4d(path);
    seq = resample_if(decode_model_c4d(m, is_bytes ? "model.c4d" : path.string()), resample, interp);
    if (output) {
      OutputDir out(*output);
      write_mesh_sequence(out, seq, "unpacked from " + path.filename().string(), parse_mesh_formats(format));
      out.commit();
    }
  }
  return mesh_dict(seq);
}

}  // namespace
}  // namespace c4d::python

PYBIND11_MODULE(contour4d, m) {
  using namespace c4d::python;
  namespace fs = std::filesystem;
  m.doc() =
      "contour4d: segmented contours and label masks to 4D surface meshes with 1-to-1 vertex correspondence.\n"
      "Lengths in mm, times in ms, coordinates in the input's patient space (LPS unless space='ras').";
  m.attr("__version__") = "0.1.0";
  register_exceptions(m);
  m.def("read", &read_to_dict, "input"_a,
        "Reads any supported input (contour JSON, GPFile folder, Sunnybrook folder, RT structure set, label images;\n"
        "or a list of contour dicts) into {'contours': [{'frame', 'slice', 'label', 'offset_mm', 'time_ms',\n"
        "'points': (n, 3)}], 'timing',\n"
        "'repairs', 'notes', 'format', 'space', 'stack_normal', 'frames'}.\n"
        "Options as `contour4d reconstruct`'s: type, label ('all': every structure), labels, slice_axis, space,\n"
        "frame_ms, cycle_ms, exact_contours, contour_tolerance, align_slices, strict.");
  m.def("reconstruct", &reconstruct, "input"_a, "output"_a = py::none(), "keep_failed"_a = py::none(),
        "format"_a = "vtp",
        "Reconstructs INPUT (a path, a list of contour dicts, or read()'s dict) as `contour4d reconstruct` does.\n"
        "Returns {'positions': (frames, vertices, 3), 'triangles': (n, 3), 'times_ms': (frames,), 'report': dict}.\n"
        "With output= the same files as the command line are written there. Options: frame, edge, cap, method,\n"
        "threads, volume_tolerance, vertical_deformation, tiling, and read()'s. A result that fails its checks raises "
        "SolverError (exit_code 26).");
  m.def("evaluate", &evaluate_folder, "outdir"_a, "contours"_a = py::none(), "truth"_a = py::none(), "label"_a = "",
        "type"_a = std::vector<std::string>{}, "step"_a = 0.2, "sample_spacing"_a = 0.5, "self_intersections"_a = true,
        "json"_a = py::none(),
        "Measures a reconstruction folder as `contour4d evaluate` does; returns evaluation.json's content as a dict\n"
        "(written to json= when given).");
  m.def("load", &load, "path"_a, "Reads a reconstruction folder (mesh.pvd, frames/) into the mesh dict.");
  m.def("pack", &pack, "input"_a, "output"_a = py::none(), "tolerance"_a = 0.05, "normal_p99"_a = 1.5,
        "step"_a = 0.0125, "resample"_a = 0, "interp"_a = "catmull-rom", "gltf"_a = true, "gltf_step"_a = false,
        "gltf_quantized"_a = false,
        "Packs a reconstruction folder (or a mesh dict) into model.c4d as `contour4d pack` does; written to output=\n"
        "(default INPUT/model.c4d for a folder) with model.glb beside it. Returns the figures and the bytes.");
  m.def("unpack", &unpack, "model"_a, "output"_a = py::none(), "resample"_a = 0, "interp"_a = "catmull-rom",
        "format"_a = "vtp",
        "Decodes a model.c4d (path or bytes) into the mesh dict; output= writes the folder as `contour4d unpack`.");
}
