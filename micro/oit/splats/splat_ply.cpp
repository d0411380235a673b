#include "oit/splats/splat_ply.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

namespace oitbench::oit {

namespace {

// Real spherical harmonics' constants, degrees 0 to 3 (the same basis and signs as graphdeco-inria's
// trainer, so its files' colours come out as its viewer shows them).
constexpr double kShC0 = 0.28209479177387814;
constexpr double kShC1 = 0.4886025119029199;
constexpr std::array<double, 5> kShC2 = {1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                                         -1.0925484305920792, 0.5462742152960396};
constexpr std::array<double, 7> kShC3 = {-0.5900435899266435, 2.890611442640554,   -0.4570457994644658,
                                         0.3731763325901154,  -0.4570457994644658, 1.445305721320277,
                                         -0.5900435899266435};

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Type> parse_type(const std::string& s) {
  if (s == "char" || s == "int8") return Type::Int8;
  if (s == "uchar" || s == "uint8") return Type::UInt8;
  if (s == "short" || s == "int16") return Type::Int16;
  if (s == "ushort" || s == "uint16") return Type::UInt16;
  if (s == "int" || s == "int32") return Type::Int32;
  if (s == "uint" || s == "uint32") return Type::UInt32;
  if (s == "float" || s == "float32") return Type::Float32;
  if (s == "double" || s == "float64") return Type::Float64;
  return std::nullopt;
}

size_t type_size(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8:
      return 1;
    case Type::Int16:
    case Type::UInt16:
      return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 0;
}

// A little-endian value of type t at p, whatever the host's byte order.
double decode(const unsigned char* p, Type t) {
  std::uint64_t u = 0;
  const size_t n = type_size(t);
  for (size_t i = 0; i < n; ++i) u |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  switch (t) {
    case Type::Int8:
      return static_cast<std::int8_t>(u);
    case Type::UInt8:
      return static_cast<double>(u);
    case Type::Int16:
      return static_cast<std::int16_t>(u);
    case Type::UInt16:
      return static_cast<double>(u);
    case Type::Int32:
      return static_cast<std::int32_t>(u);
    case Type::UInt32:
      return static_cast<double>(u);
    case Type::Float32:
      return std::bit_cast<float>(static_cast<std::uint32_t>(u));
    case Type::Float64:
      return std::bit_cast<double>(u);
  }
  return 0;
}

struct Property {
  std::string name;
  Type type;
  size_t offset;  // in a binary vertex
  int line;       // in the header
};

// The properties a splat needs, in the order read_values() hands them on (the f_rest_* follow).
constexpr std::array<const char*, 14> kRequired = {"x",      "y",       "z",       "f_dc_0",  "f_dc_1",
                                                   "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                                                   "rot_0",  "rot_1",   "rot_2",   "rot_3"};
enum Field { X, Y, Z, Dc0, Dc1, Dc2, Opacity, Scale0, Scale1, Scale2, Rot0, Rot1, Rot2, Rot3, kFields };

struct Header : SplatPlyHeader {
  std::vector<Property> props;  // the vertex element's, in file order
  std::vector<size_t> wanted;   // indices into props: kRequired's order, then f_rest_0..K-1
};

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw SplatFileError(path + ": " + what); }
[[noreturn]] void fail_line(const std::string& path, int line, const std::string& what) {
  fail(path, "header line " + std::to_string(line) + ": " + what);
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

std::uint64_t parse_count(const std::string& path, int line, const std::string& s) {
  std::uint64_t n = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
  if (ec != std::errc() || end != s.data() + s.size())
    fail_line(path, line, "element vertex count \"" + s + "\" is not a whole number of vertices");
  return n;
}

// The properties' names checked: each required one present, float or double; the f_rest_* a degree's set.
void find_wanted(const std::string& path, Header& h, int end_line) {
  auto index_of = [&](const std::string& name) -> std::optional<size_t> {
    for (size_t i = 0; i < h.props.size(); ++i)
      if (h.props[i].name == name) return i;
    return std::nullopt;
  };
  auto want = [&](const std::string& name) {
    auto i = index_of(name);
    if (!i) return false;
    const Property& p = h.props[*i];
    if (p.type != Type::Float32 && p.type != Type::Float64)
      fail_line(path, p.line, "property \"" + name + "\" must be float or double (a real number), not an integer type");
    h.wanted.push_back(*i);
    return true;
  };
  std::string missing;
  for (const char* name : kRequired)
    if (!want(name)) missing += (missing.empty() ? "" : ", ") + std::string(name);
  if (!missing.empty())
    fail_line(path, end_line,
              "the vertex element lacks the 3DGS properties " + missing +
                  " (a splat needs x y z, f_dc_0..2, opacity, scale_0..2 and rot_0..3)");
  size_t rest = 0;
  for (const auto& p : h.props)
    if (p.name.starts_with("f_rest_")) ++rest;
  const std::array<size_t, 4> per_degree = {0, 9, 24, 45};
  auto degree = std::find(per_degree.begin(), per_degree.end(), rest);
  if (degree == per_degree.end())
    fail_line(
        path, end_line,
        std::to_string(rest) + " f_rest_* properties: expected 0, 9, 24 or 45 (spherical harmonics of degree 0 to 3)");
  h.sh_degree = static_cast<int>(degree - per_degree.begin());
  for (size_t k = 0; k < rest; ++k)
    if (!want("f_rest_" + std::to_string(k)))
      fail_line(path, end_line,
                "f_rest_" + std::to_string(k) + " is missing: the " + std::to_string(rest) +
                    " f_rest_* properties must be f_rest_0 to f_rest_" + std::to_string(rest - 1));
}

// One header line of the vertex element or before it; `state` says which element is being declared.
void header_line(const std::string& path, Header& h, int n, const std::vector<std::string>& w, std::string& element,
                 bool& have_vertex) {
  if (w[0] == "comment" || w[0] == "obj_info") return;
  if (w[0] == "format") {
    if (w.size() != 3) fail_line(path, n, "expected \"format binary_little_endian 1.0\" or \"format ascii 1.0\"");
    if (w[1] == "binary_big_endian")
      fail_line(path, n, "binary_big_endian is not read: convert the file to binary_little_endian");
    if (w[1] != "binary_little_endian" && w[1] != "ascii") fail_line(path, n, "unknown format \"" + w[1] + "\"");
    if (w[2] != "1.0") fail_line(path, n, "format version " + w[2] + ": only 1.0 is read");
    h.ascii = w[1] == "ascii";
    return;
  }
  if (w[0] == "element") {
    if (w.size() != 3) fail_line(path, n, "expected \"element NAME COUNT\"");
    element = w[1];
    if (element == "vertex") {
      if (have_vertex) fail_line(path, n, "a second vertex element");
      have_vertex = true;
      h.count = parse_count(path, n, w[2]);
    } else if (!have_vertex) {
      fail_line(path, n,
                "element \"" + element + "\" before the vertex element: only the vertex element is read, first");
    }
    return;
  }
  if (w[0] == "property") {
    if (element.empty()) fail_line(path, n, "a property before any element");
    if (element != "vertex") return;  // a later element's: never read
    if (w.size() >= 2 && w[1] == "list") fail_line(path, n, "list properties are not read in the vertex element");
    if (w.size() != 3) fail_line(path, n, "expected \"property TYPE NAME\"");
    auto t = parse_type(w[1]);
    if (!t) fail_line(path, n, "unknown property type \"" + w[1] + "\"");
    for (const auto& p : h.props)
      if (p.name == w[2]) fail_line(path, n, "property \"" + w[2] + "\" declared twice");
    h.props.push_back({w[2], *t, h.stride, n});
    h.stride += type_size(*t);
    return;
  }
  fail_line(path, n,
            "unexpected \"" + w[0].substr(0, 40) + (w[0].size() > 40 ? "..." : "") +
                "\" (expected format, element, property, comment or end_header)");
}

Header parse_header(const std::string& path, std::istream& in, std::uint64_t file_size) {
  // The header is read from its first 64 KiB at most: a file of one endless line is not read whole.
  constexpr size_t kMaxHeaderBytes = 1 << 16;
  std::string head(static_cast<size_t>(std::min<std::uint64_t>(file_size, kMaxHeaderBytes)), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  Header h;
  std::string element;
  bool have_format = false, have_vertex = false;
  size_t at = 0;
  for (int n = 1;; ++n) {
    const size_t eol = head.find('\n', at);
    if (eol == std::string::npos) {
      if (head.size() < kMaxHeaderBytes) fail(path, "the file ends inside its header (line " + std::to_string(n) + ")");
      fail(path, "no end_header in the first 64 KiB: not a 3DGS PLY file");
    }
    std::string line = head.substr(at, eol - at);
    at = eol + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (n == 1) {
      if (line != "ply") fail_line(path, 1, "not a PLY file (its first line is not \"ply\")");
      continue;
    }
    auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "end_header") {
      if (!have_format) fail_line(path, n, "no format line before end_header");
      if (!have_vertex) fail_line(path, n, "no vertex element (\"element vertex N\")");
      find_wanted(path, h, n);
      break;
    }
    have_format = have_format || w[0] == "format";
    header_line(path, h, n, w, element, have_vertex);
  }
  h.data_offset = at;
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  // Refuse a count the file cannot hold before anything is allocated for it.
  const std::uint64_t left = file_size - std::min(file_size, h.data_offset);
  const std::uint64_t least = h.ascii ? 2 * h.props.size() : h.stride;  // an ascii value takes a digit and a space
  if (h.count > left / least) {
    std::ostringstream s;
    s << "the header says " << h.count << " vertices of "
      << (h.ascii ? std::to_string(h.props.size()) + " values" : std::to_string(h.stride) + " bytes") << " but only "
      << left << " bytes follow it: the file is truncated or its count is wrong";
    fail(path, s.str());
  }
  return h;
}

std::string text_of(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Streams the wanted values of the first `max_count` vertices to `take(index, values)`, checking that
// each is finite.
void read_values(const std::string& path, const Header& h, std::istream& in, std::uint64_t max_count,
                 const std::function<void(std::uint64_t, const double*)>& take) {
  const std::uint64_t n = std::min(h.count, max_count);
  std::vector<double> all(h.props.size()), values(h.wanted.size());
  auto check_and_take = [&](std::uint64_t i) {
    for (size_t k = 0; k < h.wanted.size(); ++k) {
      values[k] = all[h.wanted[k]];
      if (!std::isfinite(values[k]))
        fail(path, "vertex " + std::to_string(i) + ": property " + h.props[h.wanted[k]].name + " is " +
                       text_of(values[k]) + " (expected a finite number)");
    }
    take(i, values.data());
  };
  if (h.ascii) {
    std::string line;
    for (std::uint64_t i = 0; i < n; ++i) {
      if (!std::getline(in, line))
        fail(path, "the file ends after " + std::to_string(i) + " of its " + std::to_string(h.count) + " vertices");
      const char* p = line.c_str();
      for (size_t k = 0; k < all.size(); ++k) {
        char* end = nullptr;
        all[k] = std::strtod(p, &end);
        if (end == p)
          fail(path, "vertex " + std::to_string(i) + ": expected " + std::to_string(all.size()) + " numbers, got " +
                         std::to_string(k) + " (property " + h.props[k].name + ")");
        p = end;
      }
      check_and_take(i);
    }
    return;
  }
  constexpr std::uint64_t kChunk = 4096;
  std::vector<unsigned char> buf(static_cast<size_t>(std::min(n, kChunk) * h.stride));
  for (std::uint64_t first = 0; first < n; first += kChunk) {
    const std::uint64_t m = std::min(kChunk, n - first);
    in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(m * h.stride));
    if (static_cast<std::uint64_t>(in.gcount()) != m * h.stride)
      fail(path, "the file ends inside vertex " + std::to_string(first + in.gcount() / h.stride) + " of " +
                     std::to_string(h.count));
    for (std::uint64_t i = 0; i < m; ++i) {
      const unsigned char* v = buf.data() + i * h.stride;
      for (size_t k = 0; k < all.size(); ++k) all[k] = decode(v + h.props[k].offset, h.props[k].type);
      check_and_take(first + i);
    }
  }
}

std::ifstream open_input(const std::string& path, std::uint64_t& size) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(path, "cannot read the splat file: no such file");
  if (!std::filesystem::is_regular_file(status)) fail(path, "not a regular file");
  size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot read the splat file's size: " + ec.message());
  if (size > kMaxSplatFileBytes)
    fail(path, "the splat file is " + std::to_string(size) + " bytes; the most read is " +
                   std::to_string(kMaxSplatFileBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the splat file");
  return in;
}

// A splat from the wanted values; `rest` points at the f_rest values as floats.
Splat make_splat(const std::string& path, std::uint64_t i, const double* v, const float* rest, int degree,
                 glm::vec3 eye, glm::vec3 offset) {
  Splat s;
  s.position = glm::vec3(v[X], v[Y], v[Z]) + offset;
  for (int k = 0; k < 3; ++k) {
    const float e = static_cast<float>(std::exp(v[Scale0 + k]));
    if (!std::isfinite(e))
      fail(path, "vertex " + std::to_string(i) + ": property scale_" + std::to_string(k) + " is " +
                     text_of(v[Scale0 + k]) + ": its exponential (the standard deviation) overflows");
    s.scale[k] = e;
  }
  s.opacity = static_cast<float>(1.0 / (1.0 + std::exp(-v[Opacity])));
  const glm::dvec4 q(v[Rot0], v[Rot1], v[Rot2], v[Rot3]);
  const double len = std::sqrt(glm::dot(q, q));
  if (!(len > 1e-30))
    fail(path, "vertex " + std::to_string(i) + ": rot_0..3 is the zero quaternion (a rotation needs a non-zero one)");
  s.rotation = glm::quat(static_cast<float>(q.x / len), static_cast<float>(q.y / len), static_cast<float>(q.z / len),
                         static_cast<float>(q.w / len));
  const float dc[3] = {static_cast<float>(v[Dc0]), static_cast<float>(v[Dc1]), static_cast<float>(v[Dc2])};
  const glm::vec3 d = s.position - eye;
  const float l = glm::length(d);
  s.colour = sh_colour(degree, dc, rest, l > 0 ? d / l : glm::vec3(0, 0, 1));
  return s;
}

void put_float(std::ostream& out, float f) {
  const std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  const char b[4] = {static_cast<char>(u & 0xff), static_cast<char>((u >> 8) & 0xff),
                     static_cast<char>((u >> 16) & 0xff), static_cast<char>((u >> 24) & 0xff)};
  out.write(b, 4);
}

}  // namespace

SplatPlyHeader read_splat_ply_header(const std::string& path) {
  std::uint64_t size = 0;
  std::ifstream in = open_input(path, size);
  return parse_header(path, in, size);
}

SplatList read_splat_ply(const std::string& path, glm::vec3 eye, std::uint64_t max_count, glm::vec3 offset) {
  std::uint64_t size = 0;
  std::ifstream in = open_input(path, size);
  const Header h = parse_header(path, in, size);
  SplatList out;
  out.reserve(static_cast<size_t>(std::min(h.count, max_count)));  // bounded by the file's size (parse_header)
  std::vector<float> rest(h.wanted.size() - kFields);
  read_values(path, h, in, max_count, [&](std::uint64_t i, const double* v) {
    for (size_t k = 0; k < rest.size(); ++k) rest[k] = static_cast<float>(v[kFields + k]);
    out.push_back(make_splat(path, i, v, rest.data(), h.sh_degree, eye, offset));
  });
  return out;
}

void check_splat_ply(const std::string& path) {
  std::uint64_t size = 0;
  std::ifstream in = open_input(path, size);
  const Header h = parse_header(path, in, size);
  std::vector<float> rest(h.wanted.size() - kFields);
  read_values(path, h, in, UINT64_MAX, [&](std::uint64_t i, const double* v) {
    for (size_t k = 0; k < rest.size(); ++k) rest[k] = static_cast<float>(v[kFields + k]);
    (void)make_splat(path, i, v, rest.data(), h.sh_degree, glm::vec3(0.0f), glm::vec3(0.0f));
  });
}

glm::vec3 sh_colour(int degree, const float* dc, const float* rest, glm::vec3 dir) {
  const int per_channel = (degree + 1) * (degree + 1) - 1;
  const double x = dir.x, y = dir.y, z = dir.z;
  const double xx = x * x, yy = y * y, zz = z * z;
  // The basis functions 1..15 along dir (0 is the constant C0).
  const std::array<double, 15> basis = {-kShC1 * y,
                                        kShC1 * z,
                                        -kShC1 * x,
                                        kShC2[0] * x * y,
                                        kShC2[1] * y * z,
                                        kShC2[2] * (2 * zz - xx - yy),
                                        kShC2[3] * x * z,
                                        kShC2[4] * (xx - yy),
                                        kShC3[0] * y * (3 * xx - yy),
                                        kShC3[1] * x * y * z,
                                        kShC3[2] * y * (4 * zz - xx - yy),
                                        kShC3[3] * z * (2 * zz - 3 * xx - 3 * yy),
                                        kShC3[4] * x * (4 * zz - xx - yy),
                                        kShC3[5] * z * (xx - yy),
                                        kShC3[6] * x * (xx - 3 * yy)};
  glm::vec3 c;
  for (int ch = 0; ch < 3; ++ch) {
    double sum = 0.5 + kShC0 * dc[ch];
    for (int k = 0; k < per_channel; ++k) sum += basis[k] * rest[ch * per_channel + k];
    c[ch] = static_cast<float>(std::max(sum, 0.0));
  }
  return c;
}

void write_splat_ply(const std::string& path, const SplatList& splats, int sh_degree, const std::vector<float>& rest) {
  const size_t per_channel = static_cast<size_t>((sh_degree + 1) * (sh_degree + 1) - 1);
  if (sh_degree < 0 || sh_degree > 3 || (sh_degree > 0 && rest.size() != splats.size() * 3 * per_channel))
    fail(path, "write_splat_ply: degree " + std::to_string(sh_degree) + " needs " +
                   std::to_string(splats.size() * 3 * per_channel) + " f_rest values, got " +
                   std::to_string(rest.size()));
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(path, "cannot write the splat file");
  out << "ply\nformat binary_little_endian 1.0\ncomment written by oitbench (a 3D Gaussian splatting file)\n"
      << "element vertex " << splats.size() << "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"})
    out << "property float " << p << "\n";
  for (size_t k = 0; k < 3 * per_channel; ++k) out << "property float f_rest_" << k << "\n";
  for (const char* p : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    out << "property float " << p << "\n";
  out << "end_header\n";
  for (size_t i = 0; i < splats.size(); ++i) {
    const Splat& s = splats[i];
    for (float f : {s.position.x, s.position.y, s.position.z, 0.0f, 0.0f, 0.0f}) put_float(out, f);
    for (int c = 0; c < 3; ++c) put_float(out, static_cast<float>((s.colour[c] - 0.5) / kShC0));
    for (size_t k = 0; k < 3 * per_channel; ++k) put_float(out, rest[i * 3 * per_channel + k]);
    const double o = std::clamp(static_cast<double>(s.opacity), 1e-6, 1.0 - 1e-6);
    put_float(out, static_cast<float>(std::log(o / (1.0 - o))));
    for (int k = 0; k < 3; ++k) put_float(out, std::log(std::max(s.scale[k], 1e-30f)));
    for (float f : {s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z}) put_float(out, f);
  }
  out.close();
  if (!out) fail(path, "writing the splat file failed");
}

}  // namespace oitbench::oit
