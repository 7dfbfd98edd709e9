#pragma once
// A reader of particle files written from the format specifications alone, independent of the
// writer (engine/record/particle_files.cpp), for the tests that read exported particles back:
//
//   PLY (Turk 1994, "PLY polygon file format"): an ASCII header "ply", "format binary_little_endian
//   1.0", "element vertex N" and its "property TYPE NAME" lines up to "end_header\n", then N records
//   of the properties in header order, little-endian, packed. Any scalar type of the spec is read.
//   VTK XML PolyData (VTK file formats, "XML File Formats"): the XML header is tokenized into
//   elements, whose nesting is checked (every open tag closed, in order); a Piece's NumberOfPoints
//   and its DataArrays (type, Name, NumberOfComponents, format="appended", offset) are read, and
//   each array's block at "_" + offset: a UInt64 (header_type) byte count, then the values.
//
// Both give the values per scalar name, converted to double (exact for every float and integer the
// files hold): PLY's properties by their own names; VTP's Points as x, y, z, a 3-component array A
// as A0, A1, A2 (velocity: vx, vy, vz, to match PLY), a 1-component one by its name.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ranryu::test {

struct PointCloud {
    std::size_t count = 0;
    std::vector<std::string> names;                        // scalar names in file order
    std::map<std::string, std::vector<double>> values;     // per name, count values
    std::map<std::string, std::string> types;              // per name: PLY's or VTK's type
    // VTP only
    std::vector<std::string> elements;                     // the XML elements' names, in document order
    std::map<std::string, std::string> piece;              // the Piece's attributes
    std::vector<double> connectivity, offsets;             // Verts
};

namespace particle_reader_detail {

inline std::string read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + p.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Size of a scalar type, PLY or VTK name; 0 if unknown.
inline std::size_t type_size(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8" || t == "Int8" || t == "UInt8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16" || t == "Int16" || t == "UInt16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32" || t == "Int32" ||
        t == "UInt32" || t == "Float32")
        return 4;
    if (t == "double" || t == "float64" || t == "Int64" || t == "UInt64" || t == "Float64") return 8;
    return 0;
}

// Little-endian bytes at p as a value of type t, assembled byte by byte.
inline double decode(const std::string& t, const unsigned char* p) {
    std::uint64_t u = 0;
    const std::size_t n = type_size(t);
    for (std::size_t b = 0; b < n; ++b) u |= std::uint64_t(p[b]) << (8 * b);
    const bool is_signed = t == "char" || t == "int8" || t == "Int8" || t == "short" || t == "int16" || t == "Int16" ||
                           t == "int" || t == "int32" || t == "Int32" || t == "Int64";
    const bool is_float = t == "float" || t == "float32" || t == "Float32" || t == "double" || t == "float64" || t == "Float64";
    if (is_float) {
        if (n == 4) {
            float f;
            const std::uint32_t w = std::uint32_t(u);
            std::memcpy(&f, &w, 4);
            return f;
        }
        double d;
        std::memcpy(&d, &u, 8);
        return d;
    }
    if (is_signed) {
        const std::uint64_t sign = std::uint64_t(1) << (8 * n - 1);
        return n == 8 ? double(std::int64_t(u)) : double(std::int64_t(u ^ sign) - std::int64_t(sign));
    }
    return double(u);
}

// key="value" pairs of a tag's text.
inline std::map<std::string, std::string> attributes(const std::string& tag) {
    std::map<std::string, std::string> a;
    std::size_t i = 0;
    while ((i = tag.find('=', i)) != std::string::npos) {
        std::size_t k = i;
        while (k > 0 && tag[k - 1] != ' ' && tag[k - 1] != '\n') --k;
        const std::size_t q = tag.find('"', i);
        const std::size_t e = tag.find('"', q + 1);
        if (q != i + 1 || e == std::string::npos) throw std::runtime_error("vtp: malformed attribute in <" + tag + ">");
        a[tag.substr(k, i - k)] = tag.substr(q + 1, e - q - 1);
        i = e + 1;
    }
    return a;
}

}  // namespace particle_reader_detail

inline PointCloud read_ply(const std::filesystem::path& path) {
    namespace d = particle_reader_detail;
    const std::string bytes = d::read_bytes(path);
    const std::size_t end = bytes.find("end_header\n");
    if (bytes.rfind("ply\n", 0) != 0 || end == std::string::npos) throw std::runtime_error(path.string() + ": not a PLY file");
    std::istringstream header(bytes.substr(0, end));
    PointCloud pc;
    bool vertex = false, format = false;
    std::vector<std::string> types;
    for (std::string line; std::getline(header, line);) {
        std::istringstream w(line);
        std::string word;
        w >> word;
        if (word == "format") {
            std::string f, v;
            w >> f >> v;
            if (f != "binary_little_endian" || v != "1.0") throw std::runtime_error(path.string() + ": format " + f + " " + v);
            format = true;
        } else if (word == "element") {
            std::string name;
            w >> name >> pc.count;
            if (name != "vertex" || vertex) throw std::runtime_error(path.string() + ": unexpected element " + name);
            vertex = true;
        } else if (word == "property") {
            std::string type, name;
            w >> type >> name;
            if (type == "list" || d::type_size(type) == 0) throw std::runtime_error(path.string() + ": property " + type);
            pc.names.push_back(name);
            pc.types[name] = type;
            types.push_back(type);
        }
    }
    if (!format || !vertex) throw std::runtime_error(path.string() + ": no format or no vertex element");
    std::size_t record = 0;
    for (const std::string& t : types) record += d::type_size(t);
    const std::size_t body = end + std::strlen("end_header\n");
    if (bytes.size() != body + record * pc.count)
        throw std::runtime_error(path.string() + ": " + std::to_string(bytes.size() - body) + " bytes of data for " +
                                 std::to_string(pc.count) + " records of " + std::to_string(record));
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + body);
    for (const std::string& n : pc.names) pc.values[n].reserve(pc.count);
    for (std::size_t i = 0; i < pc.count; ++i)
        for (std::size_t k = 0; k < pc.names.size(); ++k) {
            pc.values[pc.names[k]].push_back(d::decode(types[k], p));
            p += d::type_size(types[k]);
        }
    return pc;
}

inline PointCloud read_vtp(const std::filesystem::path& path) {
    namespace d = particle_reader_detail;
    const std::string bytes = d::read_bytes(path);
    const std::string opener = "<AppendedData encoding=\"raw\">";
    const std::size_t appended = bytes.find(opener);
    if (appended == std::string::npos) throw std::runtime_error(path.string() + ": no raw AppendedData");
    const std::size_t data = bytes.find('_', appended + opener.size());
    if (data == std::string::npos) throw std::runtime_error(path.string() + ": no '_' opening the appended data");
    for (std::size_t i = appended + opener.size(); i < data; ++i)
        if (!std::isspace(static_cast<unsigned char>(bytes[i]))) throw std::runtime_error(path.string() + ": text before '_'");
    const std::string closing = "</AppendedData>\n</VTKFile>\n";
    if (bytes.size() < closing.size() || bytes.find(closing, bytes.size() - closing.size() - 4) == std::string::npos)
        throw std::runtime_error(path.string() + ": does not end with </AppendedData></VTKFile>");

    // The XML before the data: elements, their nesting and attributes.
    PointCloud pc;
    const std::string xml = bytes.substr(0, appended);
    std::vector<std::string> open;
    std::map<std::string, std::string> file;
    struct Array {
        std::string parent;
        std::map<std::string, std::string> a;
    };
    std::vector<Array> arrays;
    for (std::size_t i = 0; (i = xml.find('<', i)) != std::string::npos;) {
        const std::size_t e = xml.find('>', i);
        if (e == std::string::npos) throw std::runtime_error(path.string() + ": unclosed tag");
        std::string tag = xml.substr(i + 1, e - i - 1);
        i = e + 1;
        if (tag.starts_with("?") || tag.starts_with("!--")) continue;
        if (tag.starts_with("/")) {
            if (open.empty() || open.back() != tag.substr(1)) throw std::runtime_error(path.string() + ": </" + tag + "> closes nothing open");
            open.pop_back();
            continue;
        }
        const bool empty = tag.ends_with("/");
        if (empty) tag.pop_back();
        const std::string name = tag.substr(0, tag.find(' '));
        pc.elements.push_back(name);
        const auto attrs = d::attributes(tag);
        if (name == "VTKFile") file = attrs;
        if (name == "Piece") pc.piece = attrs;
        if (name == "DataArray") arrays.push_back({open.empty() ? "" : open.back(), attrs});
        if (!empty) open.push_back(name);
    }
    if (open != std::vector<std::string>{"VTKFile"}) throw std::runtime_error(path.string() + ": elements left open before the data");
    if (file["type"] != "PolyData" || file["byte_order"] != "LittleEndian" || file["header_type"] != "UInt64")
        throw std::runtime_error(path.string() + ": VTKFile is not little-endian PolyData with UInt64 headers");
    pc.count = std::stoul(pc.piece.at("NumberOfPoints"));

    const auto* base = reinterpret_cast<const unsigned char*>(bytes.data() + data + 1);
    const std::size_t available = bytes.size() - (data + 1);
    for (const Array& arr : arrays) {
        const std::string type = arr.a.at("type"), name = arr.a.at("Name");
        const std::size_t comps = std::stoul(arr.a.count("NumberOfComponents") ? arr.a.at("NumberOfComponents") : "1");
        if (arr.a.at("format") != "appended") throw std::runtime_error(path.string() + ": " + name + " is not appended");
        const std::size_t offset = std::stoul(arr.a.at("offset"));
        const std::size_t size = d::type_size(type);
        if (size == 0 || offset + 8 > available) throw std::runtime_error(path.string() + ": " + name + " out of the data");
        const auto count = std::uint64_t(d::decode("UInt64", base + offset));
        // Point arrays hold a tuple a point; the Verts' arrays as many values as their byte count says.
        const std::size_t tuples = arr.parent == "Verts" ? std::size_t(count) / (comps * size) : pc.count;
        if (count != tuples * comps * size || offset + 8 + count > available)
            throw std::runtime_error(path.string() + ": " + name + " holds " + std::to_string(count) + " bytes");
        std::vector<std::string> scalar_names;
        if (comps == 1) scalar_names = {name};
        else if (name == "Points") scalar_names = {"x", "y", "z"};
        else if (name == "velocity") scalar_names = {"vx", "vy", "vz"};
        else
            for (std::size_t c = 0; c < comps; ++c) scalar_names.push_back(name + std::to_string(c));
        std::vector<std::vector<double>> columns(comps);
        const unsigned char* p = base + offset + 8;
        for (std::size_t i = 0; i < tuples; ++i)
            for (std::size_t c = 0; c < comps; ++c, p += size) columns[c].push_back(d::decode(type, p));
        if (arr.parent == "Verts") {
            (name == "connectivity" ? pc.connectivity : pc.offsets) = columns[0];
            continue;
        }
        if (arr.parent != "PointData" && arr.parent != "Points") throw std::runtime_error(path.string() + ": array " + name + " in " + arr.parent);
        for (std::size_t c = 0; c < comps; ++c) {
            pc.names.push_back(scalar_names[c]);
            pc.types[scalar_names[c]] = type;
            pc.values[scalar_names[c]] = std::move(columns[c]);
        }
    }
    return pc;
}

}  // namespace ranryu::test
