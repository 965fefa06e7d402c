// A hand-written PLY reader (Debian packages no PLY library). The file is read whole (by the
// input-file policy, image/file_read.h), the header is parsed into a small description of
// elements and properties, the declared counts are checked against the bytes that actually
// follow, and then one templated body reader walks the data with either an ascii or a binary
// cursor. Internally problems are thrown as PlyProblem (text only);
// readPly() turns them into SceneError so that every message starts with the file name.
#include "scene/ceng795/ply_reader.h"

#include "image/file_read.h"
#include "scene/scene_error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace pt {
namespace {

struct PlyProblem : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& problem) { throw PlyProblem(problem); }

// File content echoed in a message is bounded and made printable: a binary or hostile file must
// not be able to produce a multi-line or megabyte-long error.
std::string printable(std::string_view text) {
    constexpr size_t kMax = 32;
    std::string out;
    for (size_t i = 0; i < text.size() && i < kMax; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
    }
    if (text.size() > kMax) out += "...";
    return out;
}

std::string inQuotes(std::string_view text) { return "'" + printable(text) + "'"; }

// ---------------------------------------------------------------------------------------------
// Property types

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct TypeInfo {
    std::string_view name;
    size_t size;
    int64_t min, max; // range of the integer types; unused for floats
};

constexpr TypeInfo kTypeInfo[] = {
    {"char", 1, INT8_MIN, INT8_MAX},
    {"uchar", 1, 0, UINT8_MAX},
    {"short", 2, INT16_MIN, INT16_MAX},
    {"ushort", 2, 0, UINT16_MAX},
    {"int", 4, INT32_MIN, INT32_MAX},
    {"uint", 4, 0, UINT32_MAX},
    {"float", 4, 0, 0},
    {"double", 8, 0, 0},
};

const TypeInfo& info(Type t) { return kTypeInfo[static_cast<size_t>(t)]; }
bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

Type parseType(std::string_view name) {
    struct Alias {
        std::string_view name;
        Type type;
    };
    // The original PLY names and the sized names that newer exporters (e.g. Blender) write.
    static constexpr Alias kAliases[] = {
        {"char", Type::Int8},
        {"int8", Type::Int8},
        {"uchar", Type::UInt8},
        {"uint8", Type::UInt8},
        {"short", Type::Int16},
        {"int16", Type::Int16},
        {"ushort", Type::UInt16},
        {"uint16", Type::UInt16},
        {"int", Type::Int32},
        {"int32", Type::Int32},
        {"uint", Type::UInt32},
        {"uint32", Type::UInt32},
        {"float", Type::Float32},
        {"float32", Type::Float32},
        {"double", Type::Float64},
        {"float64", Type::Float64},
    };
    for (const Alias& a : kAliases)
        if (a.name == name) return a.type;
    fail("unknown property type " + inQuotes(name));
}

// ---------------------------------------------------------------------------------------------
// Header model

// What the body reader does with a property's value.
enum class Role : uint8_t { Skip, X, Y, Z, NX, NY, NZ, U, V, Indices };
constexpr size_t kRoleCount = 10;

struct Property {
    std::string name;
    Type type = Type::Float32; // the item type for lists
    bool isList = false;
    Type countType = Type::UInt8;
    Role role = Role::Skip;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t bodyOffset = 0;
    size_t bodySize = 0;
    // Set once the element list is final (the pointers point into `elements`).
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    bool hasNormals = false;
    bool hasUvs = false;
};

// ---------------------------------------------------------------------------------------------
// Header parsing

// The next header line without its terminator ("\n" or "\r\n"). A last line without a newline is
// accepted so that an ascii file ending right after "end_header" still parses.
bool nextLine(std::string_view data, size_t& pos, std::string_view& line) {
    if (pos >= data.size()) return false;
    size_t end = data.find('\n', pos);
    const size_t next = end == std::string_view::npos ? data.size() : end + 1;
    if (end == std::string_view::npos) end = data.size();
    line = data.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = next;
    return true;
}

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    size_t begin = line.find_first_not_of(" \t");
    while (begin != std::string_view::npos) {
        size_t end = line.find_first_of(" \t", begin);
        if (end == std::string_view::npos) end = line.size();
        words.push_back(line.substr(begin, end - begin));
        begin = line.find_first_not_of(" \t", end);
    }
    return words;
}

Format parseFormat(const std::vector<std::string_view>& words) {
    if (words.size() != 3) fail("malformed format line");
    if (words[2] != "1.0") fail("unsupported PLY version " + inQuotes(words[2]));
    if (words[1] == "ascii") return Format::Ascii;
    if (words[1] == "binary_little_endian") return Format::BinaryLittle;
    if (words[1] == "binary_big_endian") return Format::BinaryBig;
    fail("unknown format " + inQuotes(words[1]));
}

Element parseElement(const std::vector<std::string_view>& words) {
    if (words.size() != 3) fail("malformed element line");
    Element e;
    e.name = words[1];
    const std::string_view text = words[2];
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), e.count);
    if (ec != std::errc() || end != text.data() + text.size())
        fail("invalid count " + inQuotes(text) + " for element " + inQuotes(e.name));
    return e;
}

Property parseProperty(const std::vector<std::string_view>& words) {
    Property p;
    if (words.size() >= 2 && words[1] == "list") {
        if (words.size() != 5) fail("malformed list property line");
        p.isList = true;
        p.countType = parseType(words[2]);
        p.type = parseType(words[3]);
        p.name = words[4];
        // A float length cannot be skipped reliably, so even unknown elements must not use one.
        if (!isInteger(p.countType)) fail("list property " + inQuotes(p.name) + " has a non-integer count type");
        return p;
    }
    if (words.size() != 3) fail("malformed property line");
    p.type = parseType(words[1]);
    p.name = words[2];
    return p;
}

// Handles one header line; returns false at end_header.
bool parseHeaderLine(std::string_view line, Header& h, bool& haveFormat) {
    const std::vector<std::string_view> words = splitWords(line);
    if (words.empty()) return true;
    const std::string_view key = words[0];
    if (key == "end_header") {
        if (words.size() != 1) fail("malformed end_header line");
        return false;
    }
    if (key == "comment" || key == "obj_info") return true;
    if (key == "format") {
        if (haveFormat) fail("more than one format line");
        h.format = parseFormat(words);
        haveFormat = true;
    } else if (key == "element") {
        h.elements.push_back(parseElement(words));
    } else if (key == "property") {
        if (h.elements.empty()) fail("property line before any element line");
        h.elements.back().properties.push_back(parseProperty(words));
    } else {
        // Most often this is body data read as header because end_header is missing.
        fail("unknown header keyword " + inQuotes(key) + " (is end_header missing?)");
    }
    return true;
}

Header parseHeader(std::string_view data) {
    size_t pos = 0;
    std::string_view line;
    if (!nextLine(data, pos, line) || line != "ply") fail("not a PLY file (the first line is not 'ply')");
    Header h;
    bool haveFormat = false;
    for (;;) {
        if (!nextLine(data, pos, line)) fail("missing end_header (the header never ends)");
        if (!parseHeaderLine(line, h, haveFormat)) break;
    }
    if (!haveFormat) fail("missing format line");
    h.bodyOffset = pos;
    h.bodySize = data.size() - pos;
    return h;
}

// ---------------------------------------------------------------------------------------------
// Interpreting the header: which properties carry positions, normals, uvs and indices

constexpr std::array<std::string_view, 14> kVertexNames = {
    "x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t", "texture_u", "texture_v", "texture_s", "texture_t"};

// The vertex properties with a known name, by index into kVertexNames. Only known names are checked
// for duplicates: that keeps the pass linear in a hostile header with millions of properties.
std::array<Property*, kVertexNames.size()> findVertexProperties(Element& vertex) {
    std::array<Property*, kVertexNames.size()> found{};
    for (Property& p : vertex.properties) {
        const auto it = std::find(kVertexNames.begin(), kVertexNames.end(), p.name);
        if (it == kVertexNames.end()) continue;
        Property*& slot = found[static_cast<size_t>(it - kVertexNames.begin())];
        if (slot) fail("duplicate vertex property " + inQuotes(p.name));
        slot = &p;
    }
    return found;
}

void assignRole(Property& p, Role role) {
    if (p.isList) fail("vertex property " + inQuotes(p.name) + " must be a scalar, not a list");
    p.role = role;
}

// Gives `roles` to all of `props` when all are present; false when none is; an error when only
// some are, since half a normal or half a uv is certainly a broken file.
bool assignGroup(std::initializer_list<Property*> props, std::initializer_list<Role> roles, const char* what) {
    const auto present = std::count_if(props.begin(), props.end(), [](Property* p) { return p != nullptr; });
    if (present == 0) return false;
    if (present != static_cast<std::ptrdiff_t>(props.size())) fail(std::string("incomplete vertex ") + what);
    auto role = roles.begin();
    for (Property* p : props) assignRole(*p, *role++);
    return true;
}

void describeVertices(Element& vertex, Header& h) {
    if (vertex.count > std::numeric_limits<uint32_t>::max()) fail("too many vertices for 32-bit indices");
    const auto f = findVertexProperties(vertex);
    for (size_t i = 0; i < 3; ++i)
        if (!f[i]) fail("vertex element has no " + inQuotes(kVertexNames[i]) + " property");
    assignGroup({f[0], f[1], f[2]}, {Role::X, Role::Y, Role::Z}, "position");
    h.hasNormals = assignGroup({f[3], f[4], f[5]}, {Role::NX, Role::NY, Role::NZ}, "normal (needs nx, ny, nz)");
    // Texture coordinate pairs in order of preference; a later complete pair is left unused.
    for (size_t pair = 6; pair < kVertexNames.size(); pair += 2) {
        if (h.hasUvs && f[pair] && f[pair + 1]) continue;
        h.hasUvs |=
            assignGroup({f[pair], f[pair + 1]}, {Role::U, Role::V}, "texture coordinate (needs both of a pair)");
    }
}

void describeFaces(Element& face) {
    Property* indices = nullptr;
    for (Property& p : face.properties) {
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (indices) fail("face element has more than one vertex index list");
        indices = &p;
    }
    if (!indices) fail("face element has no vertex_indices list");
    if (!indices->isList) fail("face property " + inQuotes(indices->name) + " must be a list");
    if (!isInteger(indices->type)) fail("face property " + inQuotes(indices->name) + " has a non-integer index type");
    indices->role = Role::Indices;
}

void describeMesh(Header& h) {
    for (Element& e : h.elements) {
        if (e.name == "vertex") {
            if (h.vertex) fail("more than one vertex element");
            describeVertices(e, h);
            h.vertex = &e;
        } else if (e.name == "face") {
            if (h.face) fail("more than one face element");
            describeFaces(e);
            h.face = &e;
        }
    }
    if (!h.vertex) fail("no vertex element");
}

// The fewest bytes one entry of `e` can take: a binary value takes its size (a list at least its
// count), an ascii value at least one character.
uint64_t minimumEntryBytes(const Element& e, Format format) {
    uint64_t bytes = 0;
    for (const Property& p : e.properties)
        bytes += format == Format::Ascii ? 1 : info(p.isList ? p.countType : p.type).size;
    return bytes;
}

// Rejects counts that the file cannot possibly hold, before anything is allocated or looped over:
// "element vertex 4000000000" in a 100-byte file must fail at once.
void checkCountsFit(const Header& h) {
    uint64_t needed = 0;
    for (const Element& e : h.elements) {
        const uint64_t perEntry = minimumEntryBytes(e, h.format);
        if (perEntry == 0) continue; // an element without properties occupies no bytes
        // Written as a division so that a huge count cannot overflow the product.
        if (e.count > (h.bodySize - needed) / perEntry)
            fail("element " + inQuotes(e.name) + " declares " + std::to_string(e.count) + " entries but only " +
                 std::to_string(h.bodySize) + " bytes of data follow the header (truncated file or corrupt count)");
        needed += e.count * perEntry;
    }
}

// ---------------------------------------------------------------------------------------------
// Cursors: the same interface over ascii tokens and binary values, so that the element readers are
// written once. Values are checked even when their property is skipped.

[[noreturn]] void truncated() { fail("unexpected end of file (truncated)"); }

class AsciiCursor {
public:
    explicit AsciiCursor(std::string_view body) : text_(body) {}

    double readReal(Type t) { return isInteger(t) ? static_cast<double>(readInteger(t)) : parseReal(nextToken()); }

    int64_t readInteger(Type t) {
        const std::string_view token = nextToken();
        const std::string_view digits = withoutPlus(token);
        int64_t value = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec != std::errc() || end != digits.data() + digits.size())
            fail("expected an integer, found " + inQuotes(token));
        if (value < info(t).min || value > info(t).max)
            fail("value " + inQuotes(token) + " is out of range for type " + std::string(info(t).name));
        return value;
    }

    void skip(Type t) { (void)readReal(t); }

    void skipItems(uint64_t n, Type t) {
        for (uint64_t i = 0; i < n; ++i) skip(t);
    }

    uint64_t readListCount(Type countType) {
        const int64_t n = readInteger(countType);
        if (n < 0) fail("negative list length " + std::to_string(n));
        // Each item needs at least one character: an early, clear error for a corrupt length.
        if (static_cast<uint64_t>(n) > text_.size() - pos_) truncated();
        return static_cast<uint64_t>(n);
    }

    // Ascii data must end with the last declared entry; anything more means the counts are wrong.
    void finish() {
        skipSpace();
        if (pos_ != text_.size()) fail("unexpected data after the last element: " + inQuotes(nextToken()));
    }

private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

    // std::from_chars rejects a leading '+', which some writers emit.
    static std::string_view withoutPlus(std::string_view token) {
        return token.size() > 1 && token[0] == '+' ? token.substr(1) : token;
    }

    static double parseReal(std::string_view token) {
        const std::string_view digits = withoutPlus(token);
        double value = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec == std::errc::result_out_of_range) fail("number " + inQuotes(token) + " is out of range");
        if (ec != std::errc() || end != digits.data() + digits.size())
            fail("expected a number, found " + inQuotes(token));
        return value;
    }

    void skipSpace() {
        while (pos_ < text_.size() && isSpace(text_[pos_])) ++pos_;
    }

    std::string_view nextToken() {
        skipSpace();
        if (pos_ == text_.size()) truncated();
        const size_t begin = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
        return text_.substr(begin, pos_ - begin);
    }

    std::string_view text_;
    size_t pos_ = 0;
};

template <bool kSwapBytes>
class BinaryCursor {
public:
    explicit BinaryCursor(std::string_view body) : data_(body.data()), left_(body.size()) {}

    double readReal(Type t) {
        switch (t) {
        case Type::Float32: return load<float>();
        case Type::Float64: return load<double>();
        default: return static_cast<double>(readInteger(t));
        }
    }

    int64_t readInteger(Type t) {
        switch (t) {
        case Type::Int8: return load<int8_t>();
        case Type::UInt8: return load<uint8_t>();
        case Type::Int16: return load<int16_t>();
        case Type::UInt16: return load<uint16_t>();
        case Type::Int32: return load<int32_t>();
        case Type::UInt32: return load<uint32_t>();
        default: fail("internal error: integer read of a floating-point property");
        }
    }

    void skip(Type t) { advance(info(t).size); }

    // readListCount() has already checked that n items fit in what is left, so this cannot overflow.
    void skipItems(uint64_t n, Type t) { advance(n * info(t).size); }

    uint64_t readListCount(Type countType, Type itemType) {
        const int64_t n = readInteger(countType);
        if (n < 0) fail("negative list length " + std::to_string(n));
        if (static_cast<uint64_t>(n) > left_ / info(itemType).size) truncated();
        return static_cast<uint64_t>(n);
    }

    // Trailing bytes after the last entry are tolerated: some writers pad binary files.
    void finish() {}

private:
    void advance(uint64_t bytes) {
        if (bytes > left_) truncated();
        data_ += bytes;
        left_ -= bytes;
    }

    template <class T>
    T load() {
        if (left_ < sizeof(T)) truncated();
        std::array<unsigned char, sizeof(T)> bytes;
        std::memcpy(bytes.data(), data_, sizeof(T));
        if constexpr (kSwapBytes) std::reverse(bytes.begin(), bytes.end());
        T value;
        std::memcpy(&value, bytes.data(), sizeof(T));
        data_ += sizeof(T);
        left_ -= sizeof(T);
        return value;
    }

    const char* data_;
    size_t left_;
};

// The ascii cursor ignores the item type when checking a list length; this gives both cursors
// one call shape for the element readers.
uint64_t readListCount(AsciiCursor& in, const Property& p) { return in.readListCount(p.countType); }
template <bool kSwap>
uint64_t readListCount(BinaryCursor<kSwap>& in, const Property& p) {
    return in.readListCount(p.countType, p.type);
}

// ---------------------------------------------------------------------------------------------
// Element readers

// Runs fn(i) for every entry of `e`, naming the entry in any error ("face 12: ...").
template <class Fn>
void forEachEntry(const Element& e, Fn&& fn) {
    uint64_t i = 0;
    try {
        for (; i < e.count; ++i) fn(i);
    } catch (const PlyProblem& problem) {
        fail(printable(e.name) + " " + std::to_string(i) + ": " + problem.what());
    }
}

template <class Cursor>
void skipProperty(Cursor& in, const Property& p) {
    if (!p.isList) return in.skip(p.type);
    in.skipItems(readListCount(in, p), p.type);
}

template <class Cursor>
void skipElement(Cursor& in, const Element& e) {
    // Without properties there is nothing to read: don't spin through a count of billions.
    if (e.properties.empty()) return;
    forEachEntry(e, [&](uint64_t) {
        for (const Property& p : e.properties) skipProperty(in, p);
    });
}

bool allFinite(const float* v, size_t n) {
    return std::all_of(v, v + n, [](float x) { return std::isfinite(x); });
}

using Slots = std::array<float, kRoleCount>;
float slot(const Slots& s, Role r) { return s[static_cast<size_t>(r)]; }

// Appends one vertex. The check happens after the conversion to float, so that a finite double
// too large for a float is caught as well.
void storeVertex(const Slots& s, const Header& h, PlyMesh& mesh) {
    const glm::vec3 position(slot(s, Role::X), slot(s, Role::Y), slot(s, Role::Z));
    if (!allFinite(&position.x, 3)) fail("non-finite vertex position");
    mesh.positions.push_back(position);
    if (h.hasNormals) {
        const glm::vec3 normal(slot(s, Role::NX), slot(s, Role::NY), slot(s, Role::NZ));
        if (!allFinite(&normal.x, 3)) fail("non-finite vertex normal");
        mesh.normals.push_back(normal);
    }
    if (h.hasUvs) {
        const glm::vec2 uv(slot(s, Role::U), slot(s, Role::V));
        if (!allFinite(&uv.x, 2)) fail("non-finite vertex texture coordinate");
        mesh.uvs.push_back(uv);
    }
}

template <class Cursor>
void readVertices(Cursor& in, const Element& e, const Header& h, PlyMesh& mesh) {
    // checkCountsFit() has bounded e.count by the file size, so reserving is safe.
    mesh.positions.reserve(e.count);
    if (h.hasNormals) mesh.normals.reserve(e.count);
    if (h.hasUvs) mesh.uvs.reserve(e.count);
    Slots slots{};
    forEachEntry(e, [&](uint64_t) {
        for (const Property& p : e.properties) {
            if (p.role == Role::Skip)
                skipProperty(in, p);
            else
                slots[static_cast<size_t>(p.role)] = static_cast<float>(in.readReal(p.type));
        }
        storeVertex(slots, h, mesh);
    });
}

template <class Cursor>
uint32_t readIndex(Cursor& in, Type t, uint64_t vertexCount) {
    const int64_t index = in.readInteger(t);
    if (index < 0 || static_cast<uint64_t>(index) >= vertexCount)
        fail("vertex index " + std::to_string(index) + " is out of range (the mesh has " + std::to_string(vertexCount) +
             " vertices)");
    return static_cast<uint32_t>(index);
}

// Reads one polygon and appends it as a fan (v0, v[k-1], v[k]). Polygons with fewer than three
// vertices yield nothing (counted in shortFaces) but their indices are still validated.
template <class Cursor>
void readPolygon(Cursor& in, const Property& p, uint64_t vertexCount, PlyMesh& mesh) {
    std::vector<glm::uvec3>& triangles = mesh.triangles;
    const uint64_t n = readListCount(in, p);
    if (n < 3) ++mesh.shortFaces;
    uint32_t first = 0, previous = 0;
    for (uint64_t k = 0; k < n; ++k) {
        const uint32_t index = readIndex(in, p.type, vertexCount);
        if (k == 0) first = index;
        if (k >= 2) triangles.emplace_back(first, previous, index);
        previous = index;
    }
}

template <class Cursor>
void readFaces(Cursor& in, const Element& e, const Header& h, PlyMesh& mesh) {
    // A face that yields a triangle takes at least 4 values (>= 4 bytes in either format), so this
    // reservation is bounded by the file size even when most faces turn out to be degenerate.
    mesh.triangles.reserve(std::min<uint64_t>(e.count, h.bodySize / 4));
    forEachEntry(e, [&](uint64_t) {
        for (const Property& p : e.properties) {
            if (p.role == Role::Indices)
                readPolygon(in, p, h.vertex->count, mesh);
            else
                skipProperty(in, p);
        }
    });
}

template <class Cursor>
PlyMesh readElements(Cursor in, const Header& h) {
    PlyMesh mesh;
    for (const Element& e : h.elements) {
        if (&e == h.vertex)
            readVertices(in, e, h, mesh);
        else if (&e == h.face)
            readFaces(in, e, h, mesh);
        else
            skipElement(in, e);
    }
    in.finish();
    return mesh;
}

PlyMesh readBody(const Header& h, std::string_view body) {
    constexpr bool kLittleHost = std::endian::native == std::endian::little;
    switch (h.format) {
    case Format::Ascii: return readElements(AsciiCursor(body), h);
    case Format::BinaryLittle: return readElements(BinaryCursor<!kLittleHost>(body), h);
    case Format::BinaryBig: return readElements(BinaryCursor<kLittleHost>(body), h);
    }
    fail("internal error: unknown format");
}

} // namespace

// The file is read by the input-file policy (image/file_read.h), whose words are this reader's.
PlyMesh readPly(const std::filesystem::path& path) {
    const FileRead file = tryReadInputFile(path);
    if (!file) throw SceneError(path.string(), describeFileProblem(file, "a PLY file"));
    return parsePly(
        std::string_view(reinterpret_cast<const char*>(file.bytes.data()), file.bytes.size()), path.string());
}

PlyMesh parsePly(std::string_view bytes, const std::string& displayName) {
    try {
        Header header = parseHeader(bytes);
        describeMesh(header);
        checkCountsFit(header);
        return readBody(header, bytes.substr(header.bodyOffset));
    } catch (const PlyProblem& problem) {
        throw SceneError(displayName, problem.what());
    }
}

} // namespace pt
