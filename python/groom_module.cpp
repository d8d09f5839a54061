// The `groom` Python module: CurveSet as numpy views of the container's own memory, the scalp's
// vectorised queries, and every op as a function.
//
// An op runs the very command the CLI runs, in this process: its inputs are handed over as in-memory
// "files" (kernel/io/memory_files.h, store_memory_scalp), its keyword arguments become the command's
// options (knot_length=1.3 -> --knot-length 1.3), and its output comes back from memory. So the
// defaults, the validation, the messages and the bytes are the CLI's by construction, not a second
// copy of every option that could drift from it.
#include "cli/command.h"
#include "fields/point_queries.h"
#include "fields/scalp_field.h"
#include "kernel/curve_set.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/memory_files.h"

#include <cstdint>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace groom;

namespace {

using CurveSetPtr = std::shared_ptr<CurveSet>;

// --- errors ---------------------------------------------------------------------------------------

PyObject* g_error = nullptr;        // groom.Error(Exception)
PyObject* g_param_error = nullptr;  // groom.ParamError(groom.Error, ValueError)
PyObject* g_warning = nullptr;      // groom.GroomWarning(UserWarning)

/// The CLI's wording turned into Python's: options become keyword names (--knot-length ->
/// knot_length) and the pointer to `groom CMD --help` goes.
std::string python_message(std::string message)
{
    static const std::regex see_help(R"( \(see `groom[^`]*`\))");
    message = std::regex_replace(message, see_help, "");
    // The in-memory files a call hands the command are named in its messages: say what they hold.
    static const std::vector<std::pair<std::regex, std::string>> memory_names{
        {std::regex(R"((-o )?mem:out\d+)"), "the result"},
        {std::regex(R"(mem:in\d+_\d+ is a \. file)"), "the curves given are not a USD file"},
        {std::regex(R"(mem:in\d+_\d+)"), "the curves"},
        {std::regex(R"(mem:scalp\d+)"), "the scalp"},
        {std::regex(R"(mem:kw\d+_([a-z0-9]+(?:-[a-z0-9]+)*))"), "the curves given as --$1"},
    };
    for (const auto& [pattern, text] : memory_names) message = std::regex_replace(message, pattern, text);
    static const std::regex option(R"(--([a-z][a-z0-9]*(?:-[a-z0-9]+)*))");
    std::string out;
    auto begin = std::sregex_iterator(message.begin(), message.end(), option);
    size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        out.append(message, last, size_t(it->position()) - last);
        std::string name = (*it)[1];
        std::replace(name.begin(), name.end(), '-', '_');
        out += name;
        last = size_t(it->position() + it->length());
    }
    out.append(message, last, std::string::npos);
    return out;
}

[[noreturn]] void raise(bool param, const std::string& message)
{
    PyErr_SetString(param ? g_param_error : g_error, python_message(message).c_str());
    throw py::error_already_set();
}

/// groom.GroomWarning with `message` (in Python's wording); throws when a warnings filter made it
/// an error.
void warn(const std::string& message)
{
    if (PyErr_WarnEx(g_warning, python_message(message).c_str(), 1) != 0) throw py::error_already_set();
}

/// Python's bool or numpy's (np.True_, a comparison's element), which a keyword takes as a flag.
bool is_bool(py::handle v)
{
    return py::isinstance<py::bool_>(v) || std::string(py::str(py::type::handle_of(v).attr("__name__"))) == "bool_";
}

// --- CurveSet <-> numpy ---------------------------------------------------------------------------

/// A numpy view of one column, sharing its memory; `owner` (the Python CurveSet) is kept alive by it.
py::object column_view(Attribute& a, py::handle owner)
{
    const py::ssize_t n = static_cast<py::ssize_t>(a.size());
    switch (a.type()) {
        case AttrType::Float: return py::array_t<float>({n}, {py::ssize_t(sizeof(float))}, a.values<float>().data(), owner);
        case AttrType::Int32: return py::array_t<int32_t>({n}, {py::ssize_t(sizeof(int32_t))}, a.values<int32_t>().data(), owner);
        case AttrType::Int64: return py::array_t<int64_t>({n}, {py::ssize_t(sizeof(int64_t))}, a.values<int64_t>().data(), owner);
        case AttrType::Float3:
            static_assert(sizeof(float3) == 3 * sizeof(float), "float3 must be three packed floats for numpy views");
            return py::array_t<float>({n, py::ssize_t(3)}, {py::ssize_t(sizeof(float3)), py::ssize_t(sizeof(float))},
                                      &a.values<float3>().data()->x, owner);
        case AttrType::String: {
            py::list l;
            for (const std::string& s : a.values<std::string>()) l.append(s);
            return l.size() == 1 ? py::object(l[0]) : py::object(l);
        }
    }
    return py::none();
}

/// Checks that `value` holds whole numbers in [lo, hi] before it is cast to an integer array:
/// pybind11's forcecast truncates 2.5 to 2 and wraps a uint64 2^64 - 1 to -1 without a word (a
/// trial: CurveSet(points, [2.5, 2.5]) made two curves of 2, a face index 2.7 named vertex 2).
void require_whole_numbers(const py::handle& value, const std::string& what, int64_t lo, int64_t hi)
{
    const py::array any = py::array::ensure(value);
    if (!any) raise(true, what + ": expected a numpy array (or a list) of integers");
    if (any.size() == 0) return;
    const char kind = any.dtype().kind();
    if (kind == 'b') return;
    if (kind != 'i' && kind != 'u' && kind != 'f') {
        raise(true, what + ": expected integers, got dtype '" + std::string(py::str(any.dtype())) + "'");
    }
    const py::module_ np = py::module_::import("numpy");
    if (kind == 'f') {
        const py::object whole = np.attr("logical_and")(np.attr("isfinite")(any), np.attr("equal")(any, np.attr("floor")(any)));
        if (!np.attr("all")(whole).cast<bool>()) {
            const auto at = np.attr("argmin")(whole).cast<py::ssize_t>();
            raise(true, what + ": expected whole numbers, found " + std::string(py::str(any.attr("flat")[py::int_(at)])) + " (value " +
                            std::to_string(at) + " of the array)");
        }
    }
    // Compared as Python ints, exact for every integer dtype (numpy compares a uint64 scalar with an
    // int64 bound in float64, which let 2^63 through as -2^63: a review).
    const py::int_ least(any.attr("min")()), most(any.attr("max")());
    if (least < py::int_(lo) || most > py::int_(hi)) {
        raise(true, what + ": values " + py::str(py::object(least)).cast<std::string>() + " to " + py::str(py::object(most)).cast<std::string>() + " are outside " +
                        std::to_string(lo) + " to " + std::to_string(hi));
    }
}


/// Sets (adding or replacing) column `name` on domain `d` from a numpy array or, on the detail
/// domain, a string: float32/float64 of shape (n,) -> float, (n, 3) -> float3, int32 -> int,
/// int64 -> int64.
void set_column(CurveSet& cs, Domain d, const std::string& name, py::handle value)
{
    if (d == Domain::Point && name == attr::P) {
        const auto arr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
        if (!arr || arr.ndim() != 2 || arr.shape(1) != 3 || size_t(arr.shape(0)) != cs.num_points()) {
            raise(true, "points: expected an array of shape (" + std::to_string(cs.num_points()) + ", 3)");
        }
        std::memcpy(cs.positions_for_write().data(), arr.data(), cs.num_points() * sizeof(float3));
        return;
    }
    const size_t n = cs.domain_size(d);
    if (d == Domain::Detail && py::isinstance<py::str>(value)) {
        cs.attributes(d).remove(name);
        cs.set_detail_string(name, value.cast<std::string>());
        return;
    }
    const py::array any = py::array::ensure(value);
    if (!any) raise(true, std::string(domain_name(d)) + " attribute '" + name + "': expected a numpy array");
    const bool vec3 = any.ndim() == 2 && any.shape(1) == 3;
    if (size_t(any.ndim() == 0 ? 1 : any.shape(0)) != n || (any.ndim() > 1 && !vec3)) {
        raise(true, std::string(domain_name(d)) + " attribute '" + name + "': expected " + std::to_string(n) +
                        " values (shape (" + std::to_string(n) + ",) or (" + std::to_string(n) + ", 3)), got shape with " +
                        std::to_string(any.ndim()) + " dimensions and " + std::to_string(any.size()) + " values");
    }
    cs.attributes(d).remove(name);
    const char kind = any.dtype().kind();
    if (kind == 'f' && vec3) {
        const auto arr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
        std::memcpy(cs.add<float3>(d, name).data(), arr.data(), n * sizeof(float3));
    }
    else if (kind == 'f') {
        const auto arr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
        std::memcpy(cs.add<float>(d, name).data(), arr.data(), n * sizeof(float));
    }
    else if ((kind == 'i' && any.itemsize() <= 4 || kind == 'u' && any.itemsize() <= 2 || kind == 'b') && !vec3) {
        const auto arr = py::array_t<int32_t, py::array::c_style | py::array::forcecast>::ensure(value);
        std::memcpy(cs.add<int32_t>(d, name).data(), arr.data(), n * sizeof(int32_t));
    }
    else if ((kind == 'i' || kind == 'u') && !vec3) {
        // uint32 into int64 (into int32 it wrapped past 2^31); uint64 only when every value fits.
        if (kind == 'u') require_whole_numbers(value, std::string(domain_name(d)) + " attribute '" + name + "'", 0, INT64_MAX);
        const auto arr = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(value);
        std::memcpy(cs.add<int64_t>(d, name).data(), arr.data(), n * sizeof(int64_t));
    }
    else {
        raise(true, std::string(domain_name(d)) + " attribute '" + name + "': unsupported dtype '" + std::string(py::str(any.dtype())) +
                        "' (expected float32/float64 (n,) or (n, 3), int32 or int64)");
    }
}

/// A CurveSet as picklable values, for pickle, copy.copy/deepcopy and multiprocessing (they said
/// "cannot pickle 'groom.CurveSet' object"): (1, counts, [(domain, name, type, bytes or strings)]),
/// every column exactly, P among them.
py::tuple curves_state(const CurveSet& cs)
{
    std::vector<int64_t> counts(cs.num_curves());
    for (size_t c = 0; c < counts.size(); ++c) counts[c] = cs.points_in(c);
    py::list columns;
    for (int d = 0; d < 3; ++d) {
        for (const Attribute& a : cs.attributes(Domain(d)).all()) {
            py::object data;
            switch (a.type()) {
                case AttrType::Float: data = py::bytes(reinterpret_cast<const char*>(a.values<float>().data()), a.size() * sizeof(float)); break;
                case AttrType::Int32: data = py::bytes(reinterpret_cast<const char*>(a.values<int32_t>().data()), a.size() * sizeof(int32_t)); break;
                case AttrType::Int64: data = py::bytes(reinterpret_cast<const char*>(a.values<int64_t>().data()), a.size() * sizeof(int64_t)); break;
                case AttrType::Float3: data = py::bytes(reinterpret_cast<const char*>(a.values<float3>().data()), a.size() * sizeof(float3)); break;
                case AttrType::String: data = py::cast(std::vector<std::string>(a.values<std::string>().begin(), a.values<std::string>().end())); break;
            }
            columns.append(py::make_tuple(d, a.name, int(a.type()), data));
        }
    }
    return py::make_tuple(1, py::cast(counts), columns);
}

std::shared_ptr<CurveSet> curves_from_state(const py::tuple& state)
{
    if (state.size() != 3 || state[0].cast<int>() != 1) raise(false, "CurveSet: unpickling: not a state this version of groom wrote");
    const auto counts = state[1].cast<std::vector<int64_t>>();
    auto cs = std::make_shared<CurveSet>(CurveSet::from_counts(std::span<const int64_t>(counts)));
    for (const py::handle item : state[2].cast<py::list>()) {
        const auto column = item.cast<py::tuple>();
        const Domain d = Domain(column[0].cast<int>());
        const std::string name = column[1].cast<std::string>();
        const AttrType type = AttrType(column[2].cast<int>());
        auto copy_in = [&](auto span) {
            const std::string bytes = column[3].cast<std::string>();
            if (bytes.size() != span.size_bytes()) raise(false, "CurveSet: unpickling: column '" + name + "' has the wrong size");
            std::memcpy(span.data(), bytes.data(), bytes.size());
        };
        switch (type) {
            case AttrType::Float: copy_in(cs->add<float>(d, name)); break;
            case AttrType::Int32: copy_in(cs->add<int32_t>(d, name)); break;
            case AttrType::Int64: copy_in(cs->add<int64_t>(d, name)); break;
            case AttrType::Float3: copy_in(d == Domain::Point && name == attr::P ? cs->positions_for_write() : cs->add<float3>(d, name)); break;
            case AttrType::String: {
                const auto strings = column[3].cast<std::vector<std::string>>();
                const auto out = cs->add<std::string>(d, name);
                if (strings.size() != out.size()) raise(false, "CurveSet: unpickling: column '" + name + "' has the wrong size");
                std::copy(strings.begin(), strings.end(), out.begin());
                break;
            }
        }
    }
    return cs;
}

/// `cs.point_attributes` and friends: a live, dict-like view of one domain's columns.
struct AttributeView {
    std::shared_ptr<CurveSet> cs;
    py::object owner;  // the Python CurveSet, so views keep it alive
    Domain domain;
};

// --- running a command in process -----------------------------------------------------------------

std::atomic<uint64_t> g_call{0};

/// Keyword arguments as the command's options: True -> a flag, False/None -> left out, sequences
/// -> "a,b,c", everything else -> str(value).
/// Keyword arguments as options. A CurveSet value (hairline=, parting=) is handed over as an
/// in-memory file named after `prefix`; its name is added to `stored` for the caller to erase.
void append_options(std::vector<std::string>& args, const py::kwargs& kw, const std::string& prefix, std::vector<std::string>& stored)
{
    for (auto item : kw) {
        std::string name = item.first.cast<std::string>();
        std::replace(name.begin(), name.end(), '_', '-');
        const py::handle v = item.second;
        if (v.is_none()) continue;
        if (name == "help") raise(true, "help: the keywords are the command's options; help(groom.FUNCTION) lists them, as `groom COMMAND -h` does");
        if (name == "output" || name == "o") raise(true, name + ": the result is returned; write it with groom.write(result, path)");
        if (name == "frames") {
            // (It ran, and said every frame "would write over this file", a file the call has not: a trial.)
            raise(true, "frames: a call returns one result, for one frame; call it once per frame (a Python loop), or run the "
                        "command from a shell with a frame range and an output pattern such as out.####.usda");
        }
        if (py::isinstance<CurveSet>(v)) {
            const std::string path = prefix + name;
            store_memory_curves(path, *v.cast<CurveSetPtr>());
            stored.push_back(path);
            args.push_back("--" + name);
            args.push_back(path);
            continue;
        }
        if (is_bool(v)) {
            if (py::bool_(py::reinterpret_borrow<py::object>(v))) args.push_back("--" + name);
            continue;
        }
        std::string text;
        if (py::isinstance<py::str>(v)) {
            text = v.cast<std::string>();
        }
        else if (py::isinstance<py::sequence>(v) || py::isinstance<py::array>(v)) {
            for (auto e : py::iter(v)) text += (text.empty() ? "" : ",") + std::string(py::str(e));
        }
        else {
            text = py::str(v);
        }
        args.push_back("--" + name);
        args.push_back(text);
    }
}

class Scalp;

/// Runs `groom COMMAND [INPUTS...] -o OUT --quiet [--scalp S] OPTIONS...` and returns OUT.
std::shared_ptr<CurveSet> run_command(const std::string& command, const std::vector<const CurveSet*>& inputs, py::object scalp,
                                      const py::kwargs& kw);

// --- the scalp --------------------------------------------------------------------------------------

class Scalp {
public:
    explicit Scalp(std::shared_ptr<const ScalpField> f) : field(std::move(f)) {}
    std::shared_ptr<const ScalpField> field;

    /// An (n,) or (n, 3) float32 array from each point's query (distance, normal, closest point):
    /// fields/point_queries.h, in parallel and by cells where the points crowd, without the GIL.
    template <class F> py::array map_points(py::array_t<float, py::array::c_style | py::array::forcecast> pts, int out_dim, F&& f) const
    {
        if (pts.ndim() != 2 || pts.shape(1) != 3) raise(true, "points: expected an array of shape (n, 3)");
        const py::ssize_t n = pts.shape(0);
        for (py::ssize_t i = 0; i < n; ++i) {
            // A NaN reached the field's arithmetic and came back as "a computation overflowed float".
            const float* q = pts.data(i, 0);
            if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) {
                raise(true, "points: row " + std::to_string(i) + " is not finite (" + format_number(q[0]) + ", " + format_number(q[1]) + ", " +
                                format_number(q[2]) + ")");
            }
        }
        py::array_t<float> out = out_dim == 1 ? py::array_t<float>({n}) : py::array_t<float>({n, py::ssize_t(3)});
        static_assert(sizeof(float3) == 3 * sizeof(float), "an (n, 3) float32 array is n float3s");
        const auto* in = reinterpret_cast<const float3*>(pts.data());
        float* o = out.mutable_data();
        {
            py::gil_scoped_release release;
            query_points(*field, std::span<const float3>(in, size_t(n)),
                         [&](size_t i, float d, const float3& nn, const float3& c) { f(d, nn, c, o + i * size_t(out_dim)); });
        }
        return out;
    }
};

std::shared_ptr<CurveSet> run_command(const std::string& command, const std::vector<const CurveSet*>& inputs, py::object scalp,
                                      const py::kwargs& kw)
{
    if (!scalp.is_none() && !py::isinstance<Scalp>(scalp) && !py::isinstance<py::str>(scalp) && !py::hasattr(scalp, "__fspath__")) {
        // scalp=123 was read as a file named "123": "no such file".
        throw py::type_error(command + ": scalp: expected a groom.Scalp or a path, got " +
                             std::string(py::str(py::type::handle_of(scalp).attr("__name__"))));
    }
    if (py::isinstance<Scalp>(scalp) && kw.contains("scalp_voxel") && !kw["scalp_voxel"].is_none()) {
        // The field is built already: the voxel asked for would be silently dropped.
        warn(command + ": scalp_voxel is for a scalp given as a mesh path; this groom.Scalp keeps its voxel (" +
             format_number(scalp.cast<std::shared_ptr<Scalp>>()->field->voxel_size()) + "): load it with groom.Scalp.load(mesh, voxel=...) instead");
    }
    const std::string id = std::to_string(g_call++);
    const std::string out_path = "mem:out" + id, scalp_path = "mem:scalp" + id;
    // The in-memory files this call stores, erased however it ends (a keyword refused, a warning a
    // filter made an error, the command failing); the output is taken before they go.
    struct CallFiles {
        std::vector<std::string> curves;
        std::string scalp;
        ~CallFiles()
        {
            for (const std::string& path : curves) erase_memory_curves(path);
            erase_memory_scalp(scalp);
        }
    } files{{out_path}, scalp_path};
    std::vector<std::string>& stored = files.curves;
    std::vector<std::string> args{command};
    for (size_t i = 0; i < inputs.size(); ++i) {
        // The arrays are live views a caller may have written NaNs into since: blamed here, on the
        // input, not later as an error writing the command's in-memory output.
        try {
            inputs[i]->validate(inputs.size() == 1 ? "curves" : "curves " + std::to_string(i));
        }
        catch (const Error& e) {
            raise(true, e.what());
        }
        const std::string in_path = "mem:in" + id + "_" + std::to_string(i);
        store_memory_curves(in_path, *inputs[i]);
        stored.push_back(in_path);
        args.push_back(in_path);
    }
    args.insert(args.end(), {"-o", out_path, "--quiet"});
    if (!scalp.is_none()) {
        args.push_back("--scalp");
        if (py::isinstance<Scalp>(scalp)) {
            store_memory_scalp(scalp_path, scalp.cast<std::shared_ptr<Scalp>>()->field);
            args.push_back(scalp_path);
        }
        else {
            args.push_back(py::str(py::module_::import("os").attr("fspath")(scalp)));
        }
    }
    append_options(args, kw, "mem:kw" + id + "_", stored);
    std::string message;
    std::vector<std::string> warnings;
    int code = 0;
    {
        py::gil_scoped_release release;
        code = cli::run_captured(args, message, &warnings);
    }
    for (std::string w : warnings) {
        // "curl: warning: the curl radius ..." -> "curl: the curl radius ..." (the category says it).
        if (const size_t at = w.find("warning: "); at != std::string::npos) w.erase(at, 9);
        warn(w);
    }
    if (code != 0) {
        // A bool for an option that takes a value went on as a bare flag: CLI11 says "count: 1
        // required INT missing". Say what was passed.
        static const std::regex missing(R"(--([a-z0-9-]+): \d+ required (\w+) missing)");
        std::smatch m;
        if (std::regex_search(message, m, missing)) {
            std::string key = m[1];
            std::replace(key.begin(), key.end(), '-', '_');
            if (kw.contains(key.c_str()) && is_bool(kw[key.c_str()])) {
                std::string type = m[2];
                std::transform(type.begin(), type.end(), type.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
                raise(true, command + ": " + key + " takes a value (" + type + "), not True/False; only flags take a bool");
            }
        }
        // A flag given a number (keep_extent=0) went on as the flag and the number as a stray word:
        // CLI11 says "unexpected argument: 0", naming no keyword (a trial).
        static const std::regex stray(R"(unexpected argument: (\S+))");
        if (std::regex_search(message, m, stray)) {
            for (auto item : kw) {
                if (is_bool(item.second) || item.second.is_none() || py::isinstance<CurveSet>(item.second)) continue;
                if (std::string(py::str(item.second)) == m[1].str()) {
                    raise(true, command + ": " + item.first.cast<std::string>() + " is a flag: pass True or False (got " + m[1].str() + ")");
                }
            }
        }
        raise(code == 2, message);
    }
    return std::make_shared<CurveSet>(take_memory_curves(out_path));
}

std::shared_ptr<CurveSet> make_curves(py::array_t<float, py::array::c_style | py::array::forcecast> points, py::object counts_given)
{
    require_whole_numbers(counts_given, "counts", INT64_MIN, INT64_MAX);
    const auto counts = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(counts_given);
    if (points.ndim() != 2 || points.shape(1) != 3) raise(true, "points: expected an array of shape (n, 3)");
    if (counts.ndim() != 1) raise(true, "counts: expected a 1-D array of points per curve");
    int64_t total = 0;
    for (py::ssize_t c = 0; c < counts.shape(0); ++c) {
        if (counts.at(c) < 1) {
            // No file format holds a curve without points (.usda wrote one its readers refuse, .obj
            // dropped it), so none is made.
            raise(true, "counts: curve " + std::to_string(c) + " has " + std::to_string(counts.at(c)) +
                            " points; every curve needs at least 1 (leave the curve out)");
        }
        total += counts.at(c);
    }
    if (total != points.shape(0)) {
        raise(true, "counts add up to " + std::to_string(total) + " points but points has " + std::to_string(points.shape(0)) + " rows");
    }
    auto cs = std::make_shared<CurveSet>(CurveSet::from_counts(std::span<const int64_t>(counts.data(), size_t(counts.shape(0)))));
    std::memcpy(cs->positions_for_write().data(), points.data(), size_t(total) * sizeof(float3));
    try {
        cs->validate("CurveSet");
    }
    catch (const Error& e) {
        raise(true, e.what());
    }
    return cs;
}

/// Converts a groom::Error thrown by library code called directly (read, write, Scalp) to Python's.
template <class F> auto guarded(F&& f)
{
    try {
        return f();
    }
    catch (const InvalidParam& e) {
        raise(true, e.what());
    }
    catch (const Error& e) {
        raise(false, e.what());
    }
}

void def_op(py::module_& m, const char* name, const char* command, bool takes_curves, bool takes_scalp, const char* doc)
{
    const std::string cmd = command;
    if (takes_curves) {
        m.def(
            name,
            [cmd](std::shared_ptr<CurveSet> curves, py::object scalp, py::kwargs kw) { return run_command(cmd, {curves.get()}, scalp, kw); },
            py::arg("curves").none(false), py::arg("scalp") = py::none(), doc);
    }
    else {
        m.def(
            name, [cmd, takes_scalp](py::object scalp, py::kwargs kw) { return run_command(cmd, {}, scalp, kw); },
            py::arg("scalp") = py::none(), doc);
    }
    (void)takes_scalp;
}

}  // namespace

PYBIND11_MODULE(groom, m)
{
    m.doc() = "groom: procedural hair grooming (braids, cornrows, edge hairs, curls, afro puffs) on real scalps.\n"
              "Every op takes keyword arguments named like the command-line options (knot_length for "
              "--knot-length) with the same defaults; see `groom COMMAND --help`.";
    m.attr("__version__") = GROOM_VERSION;

    g_warning = PyErr_NewExceptionWithDoc("groom.GroomWarning",
                                          "A result that was made but may not be what was meant (units, skipped guides).",
                                          PyExc_UserWarning, nullptr);
    m.add_object("GroomWarning", py::handle(g_warning));

    static py::exception<Error> error(m, "Error");
    g_error = error.ptr();
    {
        py::object base = py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError));
        PyObject* cls = PyErr_NewExceptionWithDoc("groom.ParamError", "A parameter outside its valid range (also a ValueError).",
                                                  base.ptr(), nullptr);
        m.add_object("ParamError", py::handle(cls));
        g_param_error = cls;
    }

    // An object made by __new__ without __init__ (CurveSet, Scalp, AttributeView) has no holder; every
    // method takes the holder, so pybind11 refuses it, in its own terms ("Unable to cast from non-held
    // to held instance"), which name nothing a user wrote. As a reference it read unmade memory and
    // crashed the interpreter.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        }
        catch (const py::cast_error& e) {
            if (std::string(e.what()).find("non-held to held") == std::string::npos) throw;
            PyErr_SetString(PyExc_TypeError, "groom: this object holds nothing (it was made by __new__ without __init__); make "
                                             "curves with groom.CurveSet(points, counts) or groom.read(path), a scalp with "
                                             "groom.Scalp.load(path)");
        }
    });

    py::class_<AttributeView, std::shared_ptr<AttributeView>>(m, "AttributeView", "The columns of one domain, dict-like; values are numpy views")
        .def("keys",
             [](const std::shared_ptr<AttributeView>& v) {
                 std::vector<std::string> k;
                 for (const Attribute& a : v->cs->attributes(v->domain).all()) k.push_back(a.name);
                 return k;
             })
        .def("__iter__", [](const std::shared_ptr<AttributeView>& v) {
            std::vector<std::string> k;
            for (const Attribute& a : v->cs->attributes(v->domain).all()) k.push_back(a.name);
            return py::iter(py::cast(k));
        })
        .def("__len__", [](const std::shared_ptr<AttributeView>& v) { return v->cs->attributes(v->domain).count(); })
        .def("__contains__", [](const std::shared_ptr<AttributeView>& v, const std::string& k) { return v->cs->attributes(v->domain).find(k) != nullptr; })
        .def("__getitem__",
             [](const std::shared_ptr<AttributeView>& v, const std::string& k) {
                 Attribute* a = v->cs->attributes(v->domain).find(k);
                 if (!a) throw py::key_error(std::string(domain_name(v->domain)) + " attribute '" + k + "' does not exist");
                 return column_view(*a, v->owner);
             })
        .def("__setitem__", [](const std::shared_ptr<AttributeView>& v, const std::string& k, py::handle value) { set_column(*v->cs, v->domain, k, value); })
        .def("__delitem__", [](const std::shared_ptr<AttributeView>& v, const std::string& k) {
            if (v->domain == Domain::Point && k == attr::P) raise(true, "point attribute 'P' (the positions) cannot be removed");
            if (!v->cs->attributes(v->domain).remove(k)) throw py::key_error(k);
        });

    py::class_<CurveSet, std::shared_ptr<CurveSet>>(m, "CurveSet",
                                                    "Curves: an (n, 3) float32 `points` array and `counts` points per curve, "
                                                    "plus named point, curve and detail attributes")
        .def(py::init(&make_curves), py::arg("points"), py::arg("counts"))
        .def_property_readonly("num_curves", [](const CurveSetPtr& cs) { return cs->num_curves(); })
        .def_property_readonly("num_points", [](const CurveSetPtr& cs) { return cs->num_points(); })
        .def("__len__", [](const CurveSetPtr& cs) { return cs->num_curves(); })
        .def_property(
            "points", [](py::object self) { return column_view(*self.cast<CurveSetPtr>()->attributes(Domain::Point).find(attr::P), self); },
            [](const CurveSetPtr& cs, py::handle v) { set_column(*cs, Domain::Point, std::string(attr::P), v); },
            "(num_points, 3) float32 view of the positions: writing to it moves the points")
        .def_property_readonly("offsets",
                               [](const CurveSetPtr& cs) {
                                   const auto o = cs->offsets();
                                   py::array_t<int64_t> out(py::ssize_t(o.size()), o.data());
                                   out.attr("setflags")(py::arg("write") = false);  // a copy: writing to it would change nothing
                                   return out;
                               })
        .def_property_readonly("counts",
                               [](const CurveSetPtr& cs) {
                                   py::array_t<int64_t> out(py::ssize_t(cs->num_curves()));
                                   for (size_t c = 0; c < cs->num_curves(); ++c) out.mutable_at(c) = cs->points_in(c);
                                   out.attr("setflags")(py::arg("write") = false);  // a copy: writing to it would change nothing
                                   return out;
                               })
        .def_property_readonly("point_attributes",
                               [](py::object self) { return AttributeView{self.cast<std::shared_ptr<CurveSet>>(), self, Domain::Point}; })
        .def_property_readonly("curve_attributes",
                               [](py::object self) { return AttributeView{self.cast<std::shared_ptr<CurveSet>>(), self, Domain::Curve}; })
        .def_property_readonly("detail_attributes",
                               [](py::object self) { return AttributeView{self.cast<std::shared_ptr<CurveSet>>(), self, Domain::Detail}; })
        .def("copy", [](const CurveSetPtr& cs) { return std::make_shared<CurveSet>(*cs); })
        .def("__copy__", [](const CurveSetPtr& cs) { return std::make_shared<CurveSet>(*cs); })
        .def("__deepcopy__", [](const CurveSetPtr& cs, py::dict) { return std::make_shared<CurveSet>(*cs); }, py::arg("memo"))
        .def(py::pickle([](const CurveSetPtr& cs) { return curves_state(*cs); }, [](const py::tuple& state) { return curves_from_state(state); }))
        .def("__repr__", [](const CurveSetPtr& cs) {
            return "<groom.CurveSet " + std::to_string(cs->num_curves()) + " curves, " + std::to_string(cs->num_points()) + " points>";
        });

    m.def(
        "read", [](const std::filesystem::path& path) { return guarded([&] { return std::make_shared<CurveSet>(read_curves(path.string())); }); },
        py::arg("path"), "Reads a curve file (.usda .obj .ply .hair); a str or a pathlib.Path");
    m.def(
        "write",
        [](const CurveSetPtr& cs, const std::filesystem::path& path) {
            if (!cs) throw py::type_error("write: curves is None; expected a groom.CurveSet");
            std::string dropped;
            guarded([&] {
                const DroppedColumnsListener listen([&](const std::string& m) { dropped = m; });
                write_curves(*cs, path.string());
                return 0;
            });
            if (!dropped.empty()) warn("write: " + dropped);  // (ids past 2^53 had left a .ply without a word: a trial)
        },
        py::arg("curves"), py::arg("path"), "Writes curves atomically (format by extension)");

    py::class_<Scalp, std::shared_ptr<Scalp>>(m, "Scalp", "The scalp as a signed distance field (OpenVDB level set)")
        .def_static(
            "load",
            [](const std::filesystem::path& path, float voxel, const std::string& grid, const std::string& group, float fill_holes) {
                ScalpBuildParams p;
                p.voxel_size = voxel;
                p.grid = grid;
                p.group = group;
                p.fill_holes = fill_holes;
                Scalp s = guarded([&] {
                    try {
                        p.validate();
                        return Scalp(load_scalp(path.string(), p));
                    }
                    catch (const InvalidParam& e) {
                        // The loader speaks of the commands' --scalp-grid/--scalp-group: here they are grid= and group=.
                        std::string m = e.what();
                        for (const std::string name : {"grid", "group"}) {
                            m = std::regex_replace(m, std::regex("--scalp-" + name + " NAME"), name + "='NAME'");
                            m = std::regex_replace(m, std::regex("--scalp-" + name + " "), name + "=");
                        }
                        throw InvalidParam(m);
                    }
                });
                if (fill_holes > 0.0f && path.extension() == ".vdb") {
                    warn("Scalp.load: fill_holes is for meshes; " + path.string() + " is a field already, built as it was: rebuild it "
                         "with `groom scalp MESH --fill-holes " + format_number(fill_holes) + "`");
                }
                if (voxel > 0.0f && path.extension() == ".vdb" && s.field->voxel_size() != voxel) {
                    // A .vdb is read as it was built; the voxel asked for was silently dropped.
                    warn("Scalp.load: voxel " + format_number(voxel) + " is for meshes; " + path.string() + " keeps the voxel it was built with (" +
                         format_number(s.field->voxel_size()) + "): rebuild it with `groom scalp MESH --voxel " + format_number(voxel) + "`");
                }
                return s;
            },
            py::arg("path"), py::arg("voxel") = 0.0f, py::arg("grid") = "", py::arg("group") = "", py::arg("fill_holes") = 0.0f,
            "A .vdb from `groom scalp` (another program's too: grid= picks its level set by name, default the grid "
            "'scalp', else the file's only float level set), or a mesh converted with the given voxel size (0 = automatic; "
            "group= keeps one OBJ object or group, e.g. the head without its eyes; fill_holes= closes open rims up to that "
            "length, as `groom scalp --fill-holes`); a str or a pathlib.Path")
        .def_static(
            "from_mesh",
            [](py::array_t<float, py::array::c_style | py::array::forcecast> vertices, py::object faces_given, float voxel, float fill_holes) {
                require_whole_numbers(faces_given, "faces", INT32_MIN, INT32_MAX);
                const auto faces = py::array_t<int32_t, py::array::c_style | py::array::forcecast>::ensure(faces_given);
                if (vertices.ndim() != 2 || vertices.shape(1) != 3) raise(true, "vertices: expected an array of shape (n, 3)");
                if (faces.ndim() != 2 || faces.shape(1) < 3) raise(true, "faces: expected an array of shape (m, 3) or (m, 4)");
                PolygonSoup soup;
                for (py::ssize_t i = 0; i < vertices.shape(0); ++i) {
                    const float3 v(vertices.at(i, 0), vertices.at(i, 1), vertices.at(i, 2));
                    // As the mesh readers refuse such a vertex by its line: left in, it reached the
                    // repair as "the mesh has no extent (all vertices at one point)" (a trial).
                    if (!isfinite(v)) raise(true, "vertices: row " + std::to_string(i) + " is not finite (" + format_xyz(v) + ")");
                    soup.points.push_back(v);
                }
                const size_t k = size_t(faces.shape(1));
                for (py::ssize_t f = 0; f < faces.shape(0); ++f) {
                    for (size_t j = 0; j < k; ++j) {
                        const int32_t index = faces.at(f, py::ssize_t(j));
                        if (index < 0 || index >= vertices.shape(0)) {
                            raise(true, "faces: row " + std::to_string(f) + " names vertex " + std::to_string(index) + "; expected 0 to " +
                                            std::to_string(vertices.shape(0) - 1));
                        }
                    }
                    soup.add_face(std::span<const int32_t>(faces.data(f, 0), k));
                }
                ScalpBuildParams p;
                p.voxel_size = voxel;
                p.fill_holes = fill_holes;
                return guarded([&] {
                    p.validate();
                    py::gil_scoped_release release;
                    return Scalp(std::make_shared<ScalpField>(build_scalp(soup, p)));
                });
            },
            py::arg("vertices"), py::arg("faces"), py::arg("voxel") = 0.0f, py::arg("fill_holes") = 0.0f,
            "A scalp from a mesh's arrays (several meshes concatenated are joined: a head and its eyeballs); voxel= as "
            "load(), fill_holes= closes open rims up to that length")
        .def_property_readonly("voxel_size", [](const std::shared_ptr<Scalp>& s) { return s->field->voxel_size(); })
        .def(
            "distance",
            [](const std::shared_ptr<Scalp>& s, py::array_t<float, py::array::c_style | py::array::forcecast> p) {
                return s->map_points(p, 1, [](float d, const float3&, const float3&, float* o) { o[0] = d; });
            },
            py::arg("points"),
            "Signed distance of each point, (n,) float32; negative inside. Within 3 voxels of the surface this is the level "
            "set's trilinear value, good to about half a voxel (more at sharp features and open rims); farther out it is the "
            "exact distance to the mesh. The same numbers as `groom probe`; a smaller voxel= tightens them near the surface.")
        .def(
            "normal",
            [](const std::shared_ptr<Scalp>& s, py::array_t<float, py::array::c_style | py::array::forcecast> p) {
                return s->map_points(p, 3, [](float, const float3& n, const float3&, float* o) { o[0] = n.x, o[1] = n.y, o[2] = n.z; });
            },
            py::arg("points"), "Unit outward normal at each point's closest surface point, (n, 3)")
        .def(
            "closest",
            [](const std::shared_ptr<Scalp>& s, py::array_t<float, py::array::c_style | py::array::forcecast> p) {
                return s->map_points(p, 3, [](float, const float3&, const float3& c, float* o) { o[0] = c.x, o[1] = c.y, o[2] = c.z; });
            },
            py::arg("points"),
            "Closest point on the scalp to each point, (n, 3): the point minus distance x normal. Within 3 voxels of the "
            "surface it lands within about half a voxel of the mesh (more at sharp features and open rims); farther out it is "
            "the exact closest point on the mesh. A smaller voxel= tightens it.")
        .def(
            "inside",
            [](const std::shared_ptr<Scalp>& s, py::array_t<float, py::array::c_style | py::array::forcecast> p) {
                py::array d = s->map_points(p, 1, [](float dist, const float3&, const float3&, float* o) { o[0] = dist; });
                return py::array(d.attr("__lt__")(0.0f));
            },
            py::arg("points"), "Whether each point is inside the scalp, (n,) bool");

    def_op(m, "braid", "braid", true, true, "Braids and cornrows from guides (`groom braid --help` lists the keywords)");
    def_op(m, "partition", "partition", true, true, "Edge hairs between adjacent braids (scalp= required)");
    def_op(m, "curl", "curl", true, true, "Curls each curve (type='4a', shapes=...)");
    def_op(m, "generate", "generate", true, true, "Hairs grown from guides over the scalp (scalp= required)");
    def_op(m, "cull", "cull", true, true, "Keeps hair outside the scalp (scalp= required)");
    def_op(m, "project", "project", true, true, "Projects curves onto the scalp (scalp= required)");
    def_op(m, "resample", "resample", true, false, "Resamples curves by count or segment length");
    def_op(m, "populate", "populate", true, false, "More hairs around each curve");
    def_op(m, "select", "select", true, false,
           "Keeps curves by ids='0-9,20', guide='3', where='width>0.01' (a list or commas for several), prim='/Root/Hair'; invert=True keeps the rest");
    def_op(m, "transform", "transform", true, false,
           "Moves curves: translate='x,y,z', rotate='x,y,z' (degrees, X then Y then Z), scale='s' or 'x,y,z', up_axis='z', units='m', from_units='cm'");
    def_op(m, "puff", "puff", false, true, "An afro puff on the scalp (scalp= required)");
    def_op(m, "cornrow_guides", "cornrow-guides", false, true, "Cornrow guide rows over the scalp (scalp= required)");
    def_op(m, "hairline", "hairline", false, true, "A default hairline around the head (scalp= required)");
    def_op(m, "parting", "parting", false, true, "Parting curves on the scalp, through='x,y,z/x,y,z/...' (scalp= required)");
    def_op(m, "edges", "edges", false, true,
           "Baby hairs laid flat in swirls along the hairline (scalp= required; hairline= and parting= take curves)");
    def_op(m, "sections", "sections", false, true,
           "One guide per section of the scalp inside the hairline, layout='grid'|'rows'|'radial' (scalp= required; hairline= takes curves)");
    m.def(
        "gather",
        [](const std::vector<std::shared_ptr<CurveSet>>& puffs, py::object scalp, py::kwargs kw) {
            std::vector<const CurveSet*> inputs;
            for (size_t i = 0; i < puffs.size(); ++i) {
                // A None in the list arrives as a null pointer (pybind11 lets it through).
                if (!puffs[i]) throw py::type_error("gather: puffs[" + std::to_string(i) + "] is None; expected a groom.CurveSet");
                inputs.push_back(puffs[i].get());
            }
            return run_command("gather", inputs, scalp, kw);
        },
        py::arg("puffs"), py::arg("scalp") = py::none(),
        "The rest of the scalp's hair gathered into puffs (each as `puff` returned it); hairline= and parting= take curves");
}
