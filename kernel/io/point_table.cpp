// Point lists in, number tables out (see point_table.h).
#include "kernel/io/point_table.h"

#include "kernel/error.h"
#include "kernel/io/io_util.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

namespace groom {
namespace {

bool is_separator(char c) { return c == ' ' || c == ',' || c == '\t' || c == '\r'; }

/// Parses the lines of text[begin, end) (whole lines) into `out`. Returns the offset of the first
/// bad line's start, or npos.
size_t parse_lines(std::string_view text, size_t begin, size_t end, std::vector<float3>& out)
{
    const char* const base = text.data();
    const char* p = base + begin;
    const char* const stop = base + end;
    while (p < stop) {
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(stop - p)));
        if (!eol) eol = stop;
        const char* q = p;
        while (q < eol && is_separator(*q)) ++q;
        if (q == eol || *q == '#') {
            p = eol + 1;
            continue;
        }
        float v[3];
        bool ok = true;
        for (int k = 0; k < 3 && ok; ++k) {
            const char* t = q;
            while (q < eol && !is_separator(*q)) ++q;
            ok = io::parse_float(std::string_view(t, size_t(q - t)), v[k]) && std::isfinite(v[k]);
            while (q < eol && is_separator(*q)) ++q;
        }
        if (!ok || q != eol) return size_t(p - base);
        out.emplace_back(v[0], v[1], v[2]);
        p = eol + 1;
    }
    return std::string_view::npos;
}

}  // namespace

bool is_npy_path(const std::string& path) { return io::extension_of(path) == "npy"; }

std::vector<float3> parse_points_text(std::string_view text, const std::string& name)
{
    // Chunks of about 1 MiB, cut after a newline: each is parsed on its own, in parallel, and the
    // pieces joined in order; the result is the same for any thread count.
    constexpr size_t kChunk = size_t(1) << 20;
    std::vector<size_t> starts{0};
    while (starts.back() < text.size()) {
        const size_t s = starts.back() + kChunk;
        if (s >= text.size()) {
            starts.push_back(text.size());
            break;
        }
        const void* nl = std::memchr(text.data() + s, '\n', text.size() - s);
        starts.push_back(nl ? size_t(static_cast<const char*>(nl) - text.data()) + 1 : text.size());
    }
    const int64_t chunks = int64_t(starts.size()) - 1;
    std::vector<std::vector<float3>> parts(size_t(std::max<int64_t>(chunks, 0)));
    std::vector<size_t> bad(parts.size(), std::string_view::npos);
    parallel_for(chunks, 1, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            parts[c].reserve((starts[c + 1] - starts[c]) / 24);
            bad[c] = parse_lines(text, starts[c], starts[c + 1], parts[c]);
        }
    });
    for (size_t c = 0; c < bad.size(); ++c) {
        if (bad[c] == std::string_view::npos) continue;
        // The first bad line: its number counted only now, on the error path.
        const size_t at = bad[c];
        const size_t line = 1 + size_t(std::count(text.begin(), text.begin() + at, '\n'));
        size_t eol = text.find('\n', at);
        if (eol == std::string_view::npos) eol = text.size();
        std::string shown(text.substr(at, eol - at));
        for (char& ch : shown)
            if (ch == ',' || ch == '\t' || ch == '\r') ch = ' ';
        throw ParseError(name + ":" + std::to_string(line) + ": expected three finite numbers 'x y z', got '" + shown + "'");
    }
    size_t total = 0;
    for (const auto& part : parts) total += part.size();
    std::vector<float3> points;
    points.reserve(total);
    for (const auto& part : parts) points.insert(points.end(), part.begin(), part.end());
    return points;
}

std::vector<float3> read_points_text(const std::string& path)
{
    const io::FileBytes file = io::read_all(path);
    return parse_points_text(file.data, file.name);
}

namespace {

/// The value of `key` in a .npy header dict ("{'descr': '<f4', 'fortran_order': False, 'shape': (3, 3), }"):
/// the text up to the next top-level comma or the closing brace, trimmed; "" when absent.
std::string npy_field(std::string_view header, std::string_view key)
{
    for (const char quote : {'\'', '"'}) {
        const std::string k = std::string(1, quote) + std::string(key) + quote;
        size_t at = header.find(k);
        if (at == std::string_view::npos) continue;
        at = header.find(':', at + k.size());
        if (at == std::string_view::npos) return {};
        size_t e = at + 1;
        int depth = 0;
        char in_string = 0;
        for (; e < header.size(); ++e) {
            const char c = header[e];
            if (in_string) {
                if (c == in_string) in_string = 0;
                continue;
            }
            if (c == '\'' || c == '"') in_string = c;
            else if (c == '(' || c == '[' || c == '{') ++depth;
            else if (c == ')' || c == ']') --depth;
            else if ((c == ',' && depth == 0) || (c == '}' && depth == 0)) break;
        }
        std::string v(header.substr(at + 1, e - at - 1));
        const size_t first = v.find_first_not_of(" \t");
        const size_t last = v.find_last_not_of(" \t");
        return first == std::string::npos ? std::string() : v.substr(first, last - first + 1);
    }
    return {};
}

uint64_t read_le(std::string_view bytes, size_t at, int size)
{
    uint64_t v = 0;
    for (int i = size - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + size_t(i)]);
    return v;
}

template <class T> T load_le(const char* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);
    if constexpr (std::endian::native == std::endian::big) {
        if constexpr (sizeof(T) == 4) v = std::bit_cast<T>(__builtin_bswap32(std::bit_cast<uint32_t>(v)));
        else v = std::bit_cast<T>(__builtin_bswap64(std::bit_cast<uint64_t>(v)));
    }
    return v;
}

}  // namespace

std::vector<float3> parse_points_npy(std::string_view bytes, const std::string& name)
{
    const std::string expected = "expected a NumPy array of shape (N, 3), dtype float32 or float64, C order";
    if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view("\x93NUMPY", 6))
        throw ParseError(name + ": not a NumPy .npy file (no '\\x93NUMPY' magic at its start); " + expected);
    const int major = static_cast<unsigned char>(bytes[6]);
    if (major < 1 || major > 3)
        throw ParseError(name + ": .npy format version " + std::to_string(major) + "." + std::to_string(static_cast<unsigned char>(bytes[7])) +
                         " (expected 1.0, 2.0 or 3.0)");
    const size_t len_size = major == 1 ? 2 : 4;
    if (bytes.size() < 8 + len_size) throw ParseError(name + ": .npy header cut short (" + std::to_string(bytes.size()) + " bytes)");
    const uint64_t header_len = read_le(bytes, 8, int(len_size));
    const size_t data_at = 8 + len_size + size_t(header_len);
    if (header_len > bytes.size() || data_at > bytes.size())
        throw ParseError(name + ": .npy header claims " + std::to_string(header_len) + " bytes, the file has " + std::to_string(bytes.size()));
    const std::string_view header = bytes.substr(8 + len_size, size_t(header_len));

    const std::string descr = npy_field(header, "descr");
    size_t item = 0;
    if (descr == "'<f4'" || descr == "\"<f4\"") item = 4;
    else if (descr == "'<f8'" || descr == "\"<f8\"") item = 8;
    else if (descr == "'>f4'" || descr == "'>f8'" || descr == "\">f4\"" || descr == "\">f8\"")
        throw ParseError(name + ": dtype " + descr + " is big-endian; expected little-endian float32 '<f4' or float64 '<f8' (numpy: a.astype('<f4'))");
    else
        throw ParseError(name + ": dtype " + (descr.empty() ? std::string("missing") : descr) +
                         "; expected float32 '<f4' or float64 '<f8' (numpy: np.save(path, a.astype(np.float32)))");
    const std::string order = npy_field(header, "fortran_order");
    if (order == "True")
        throw ParseError(name + ": Fortran (column-major) order; expected C order (numpy: np.save(path, np.ascontiguousarray(a)))");
    if (order != "False") throw ParseError(name + ": .npy header has no valid 'fortran_order' (found '" + order + "')");
    const std::string shape_text = npy_field(header, "shape");
    std::vector<uint64_t> shape;
    bool shape_ok = shape_text.size() >= 2 && shape_text.front() == '(' && shape_text.back() == ')';
    for (size_t i = 1; shape_ok && i + 1 < shape_text.size();) {
        while (i + 1 < shape_text.size() && (shape_text[i] == ' ' || shape_text[i] == ',')) ++i;
        if (i + 1 >= shape_text.size()) break;
        uint64_t v = 0;
        const auto r = std::from_chars(shape_text.data() + i, shape_text.data() + shape_text.size() - 1, v);
        if (r.ec != std::errc()) shape_ok = false;
        else {
            shape.push_back(v);
            i = size_t(r.ptr - shape_text.data());
        }
    }
    if (!shape_ok) throw ParseError(name + ": .npy header has no valid 'shape' (found '" + shape_text + "')");
    if (shape.size() != 2 || shape[1] != 3) throw ParseError(name + ": shape " + shape_text + "; expected (N, 3): one x, y, z row per point");
    const uint64_t n = shape[0];
    const uint64_t available = bytes.size() - data_at;
    if (n > available / (3 * item) || n * 3 * item != available) {
        throw ParseError(name + ": shape (" + std::to_string(n) + ", 3) of " + descr + " needs " +
                         (n > available / (3 * item) ? std::string("more than ") + std::to_string(available) : std::to_string(n * 3 * item)) +
                         " bytes of data, the file has " + std::to_string(available) + (n * 3 * item < available ? " (trailing bytes)" : " (cut short)"));
    }
    std::vector<float3> points(n);
    const char* data = bytes.data() + data_at;
    std::vector<int64_t> bad_row(1, -1);
    parallel_for(int64_t(n), 1 << 16, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            float v[3];
            for (int k = 0; k < 3; ++k) {
                const char* p = data + (size_t(i) * 3 + size_t(k)) * item;
                v[k] = item == 4 ? load_le<float>(p) : static_cast<float>(load_le<double>(p));
            }
            points[size_t(i)] = float3(v[0], v[1], v[2]);
        }
    });
    for (uint64_t i = 0; i < n; ++i) {
        if (isfinite(points[i])) continue;
        // A float64 beyond float's range turns infinite here; say so rather than show 'inf' only.
        throw ParseError(name + ": row " + std::to_string(i) + " (counting from 0): expected three finite numbers" +
                         (item == 8 ? " within float32's range" : std::string()) + ", found (" + format_number(points[i].x) + ", " +
                         format_number(points[i].y) + ", " + format_number(points[i].z) + ")");
    }
    return points;
}

std::vector<float3> read_points_npy(const std::string& path)
{
    const io::FileBytes file = io::read_all(path);
    return parse_points_npy(file.data, file.name);
}

std::vector<float3> read_points(const std::string& path)
{
    return is_npy_path(path) ? read_points_npy(path) : read_points_text(path);
}

void write_csv_table(std::ostream& out, std::string_view header, std::span<const float> values, int columns)
{
    if (columns <= 0 || values.size() % size_t(columns) != 0)
        throw InvalidParam("write_csv_table: " + std::to_string(values.size()) + " values do not fill rows of " + std::to_string(columns));
    out << header << '\n';
    const int64_t rows = int64_t(values.size() / size_t(columns));
    // Fixed chunks of rows, formatted in parallel a batch at a time (the whole table as text would
    // double the memory), each chunk into its own buffer, written in order.
    constexpr int64_t kRows = 8192, kBatch = 32;
    std::vector<std::string> text(kBatch);
    for (int64_t first = 0; first < rows; first += kRows * kBatch) {
        const int64_t chunks = std::min<int64_t>(kBatch, (rows - first + kRows - 1) / kRows);
        parallel_for(chunks, 1, [&](int64_t b, int64_t e) {
            for (int64_t c = b; c < e; ++c) {
                const int64_t r0 = first + c * kRows, r1 = std::min(rows, r0 + kRows);
                std::string& s = text[size_t(c)];
                // At most 15 characters a float ("-1.17549435e-38"), plus its separator.
                s.resize(size_t(r1 - r0) * size_t(columns) * 16);
                char* p = s.data();
                for (int64_t r = r0; r < r1; ++r) {
                    const float* row = values.data() + r * columns;
                    for (int k = 0; k < columns; ++k) {
                        p = std::to_chars(p, p + 16, row[k]).ptr;
                        *p++ = k + 1 < columns ? ',' : '\n';
                    }
                }
                s.resize(size_t(p - s.data()));
            }
        });
        for (int64_t c = 0; c < chunks; ++c) out.write(text[size_t(c)].data(), std::streamsize(text[size_t(c)].size()));
    }
}

void write_npy_table(std::ostream& out, std::span<const float> values, int columns)
{
    if (columns <= 0 || values.size() % size_t(columns) != 0)
        throw InvalidParam("write_npy_table: " + std::to_string(values.size()) + " values do not fill rows of " + std::to_string(columns));
    std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(values.size() / size_t(columns)) + ", " +
                       std::to_string(columns) + "), }";
    // Magic, version 1.0, u16 length, the dict padded with spaces to a 64-byte boundary, newline.
    const size_t total = (10 + dict.size() + 1 + 63) / 64 * 64;
    dict.append(total - 10 - dict.size() - 1, ' ');
    dict += '\n';
    const uint16_t len = uint16_t(dict.size());
    const char head[10] = {'\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0, char(len & 0xff), char(len >> 8)};
    out.write(head, 10);
    out.write(dict.data(), std::streamsize(dict.size()));
    if constexpr (std::endian::native == std::endian::little) {
        out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
    }
    else {
        for (float v : values) {
            const uint32_t u = __builtin_bswap32(std::bit_cast<uint32_t>(v));
            out.write(reinterpret_cast<const char*>(&u), 4);
        }
    }
}

}  // namespace groom
