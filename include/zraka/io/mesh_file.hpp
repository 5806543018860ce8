#pragma once
// Mesh files to zraka::mesh, by extension: .ply and glTF 2.0 (.gltf, .glb) by assimp (Debian's
// libassimp-dev), any other (.obj) by zraka's own reader (obj_file.hpp). The same reach as OBJ: positions,
// per-vertex normals (smooth shading; kept only if every part of the file has them) and texture
// coordinates (set 0, kept only if every part has them), every node's transform applied.
// uv follow texture.hpp's convention (v up from the image's bottom row), as OBJ's vt do: glTF
// counts v down from the top, and assimp turns it over on reading (test_mesh_file.cpp checks
// the texel reached at a known point).
//
//   const zraka::mesh m = zraka::read_mesh_file("scenes/meshes/sphere.ply");
//   const zraka::mesh_file_contents c = zraka::load_mesh_file("scenes/meshes/quad.gltf");
//   // c.base_colour: the file's material's base colour (glTF baseColorFactor times its
//   // baseColorTexture) as a texture, for a scene's `material: from-file`
//
// Strict like the OBJ reader: every coordinate finite and within max_coordinate, every index in
// range, counts within limits(), and every error "FILE: what" (with assimp's own words when it
// is assimp that refuses). Before assimp reads a file, zraka checks what assimp trusts: a PLY
// header line by line and its counts against the file's size, a GLB's chunk lengths, a glTF's
// image mimeTypes (fuzz_mesh found assimp 5.2 hanging, allocating 1.9 GB or crashing on each),
// so a small file cannot declare a giant allocation; every file assimp opens (a glTF's .bin
// buffers too) is a regular file within limits().file_bytes.
//
// Compiled once into zraka::compiled where zraka was built with assimp (ZRAKA_COMPILED_MESH_FILE,
// as scene_file.hpp's ZRAKA_COMPILED_SCENE_FILE): then this header only declares. Header-only,
// it includes assimp's headers and the program links assimp (README.md's table).
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/geometry/mesh.hpp>
#include <zraka/image/image.hpp>
#include <zraka/io/obj_file.hpp>
#include <zraka/textures/texture.hpp>
#include <zraka/textures/texture_file.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#if defined(ZRAKA_COMPILED_MESH_FILE)
#define ZRAKA_MESH_FILE_FN
#else
#define ZRAKA_MESH_FILE_FN inline
#endif
#if !defined(ZRAKA_COMPILED_MESH_FILE) || defined(ZRAKA_COMPILING)
#define ZRAKA_MESH_FILE_DEFINITIONS 1
#else
#define ZRAKA_MESH_FILE_DEFINITIONS 0
#endif

namespace zraka {

struct mesh_file_contents {
  mesh geometry;
  // The file's one material as an albedo: a solid colour (baseColorFactor) or an image texture
  // (baseColorTexture, decoded from sRGB, times the factor). Empty when the file has no material
  // (PLY, OBJ); `base_colour_problem` then, or when the material holds what zraka does not map
  // (several materials, emission, metal, a normal map...), says why, naming it as the file does.
  std::optional<texture> base_colour;
  std::string base_colour_problem;
};

// Reads a mesh file by its extension: .ply, .gltf, .glb by assimp, any other as OBJ; errors name `path`.
ZRAKA_MESH_FILE_FN mesh_file_contents load_mesh_file(const std::filesystem::path& path);

// Only the triangles (for a caller that gives its own material, e.g. a scene importer).
inline mesh read_mesh_file(const std::filesystem::path& path) { return load_mesh_file(path).geometry; }

namespace detail {
// A PLY header, strictly (known lines only), and its declared counts against the bytes that
// follow it: each element of an ASCII file takes at least two bytes per property ("0 "), of a
// binary one the sum of its scalar sizes (a list at least its count). Throws "NAME: ..." if the
// header is malformed, or a count cannot fit or exceeds limits().
ZRAKA_MESH_FILE_FN void check_ply_counts(std::string_view bytes, const std::string& name);
// Guards against a crash in assimp 5.2 (Debian's): an image whose "mimeType" has no '/' makes
// its glTF importer read address 1 (found by fuzz_mesh). Every JSON string is decoded (escapes
// too, as assimp's parser does) and each "mimeType" string value must hold a '/'.
ZRAKA_MESH_FILE_FN void check_gltf_json(std::string_view json, const std::string& name);
}  // namespace detail

}  // namespace zraka

#if ZRAKA_MESH_FILE_DEFINITIONS
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>
#include <sstream>
#include <system_error>
#include <vector>

#include <sys/stat.h>

namespace zraka {
namespace detail {

ZRAKA_MESH_FILE_FN void check_ply_counts(std::string_view bytes, const std::string& name) {
  // assimp takes the magic number in any case ("Ply"); anything else it refuses by name itself.
  if (bytes.size() < 3 || std::tolower(bytes[0]) != 'p' || std::tolower(bytes[1]) != 'l' || std::tolower(bytes[2]) != 'y')
    return;
  // The header, line by line, strictly: assimp's own parser loops forever on some broken headers
  // (an end_header with a stray byte), so only a header of known lines reaches it.
  struct element {
    std::string name;
    std::uint64_t count = 0, min_bytes = 0;
  };
  std::vector<element> elements;
  auto scalar_size = [](const std::string& t) -> std::uint64_t {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;  // not a PLY type
  };
  bool ascii = true, ended = false;
  std::size_t pos = 0, body = bytes.size();
  for (int line_no = 1; pos < bytes.size() && !ended; ++line_no) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos) eol = bytes.size();
    std::string line(bytes.substr(pos, eol - pos));
    pos = eol + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    auto fail = [&](const std::string& what) {
      throw error(name + ":" + std::to_string(line_no) + ": PLY header: " + what);
    };
    for (const char c : line)
      if (!((c >= ' ' && c <= '~') || c == '\t')) fail("a byte that is not printable ASCII (" + std::to_string(int(std::uint8_t(c))) + ")");
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    const std::string key = w.empty() ? "" : w[0];
    if (line_no == 1) {
      if (line != "ply" && line != "PLY") fail("the first line must be 'ply'");
    } else if (key == "comment" || key == "obj_info") {
    } else if (key == "format") {
      if (w.size() != 3 || (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      ascii = w[1] == "ascii";
    } else if (key == "element") {
      if (w.size() != 3) fail("expected 'element NAME COUNT'");
      element e;
      e.name = w[1];
      const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || p != w[2].data() + w[2].size())
        fail("the element '" + e.name + "' has the count '" + w[2] + "', not a whole number of 64 bits");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) fail("a property before any element");
      const bool list = w.size() == 5 && w[1] == "list";
      if (!(w.size() == 3 || list)) fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      if (scalar_size(w[1 + list]) == 0 || (list && scalar_size(w[3]) == 0))
        fail("unknown type in '" + line + "'");
      elements.back().min_bytes += ascii ? 2 : scalar_size(w[1 + list]);
    } else if (line == "end_header") {
      if (eol == bytes.size()) fail("'end_header' must end its line");  // assimp hangs on some files without
      ended = true;
      body = pos;
    } else {
      fail("unknown line '" + line.substr(0, 40) + "'");
    }
  }
  if (!ended) throw error(name + ": PLY header: no 'end_header' line");
  const std::uint64_t available = bytes.size() - std::min(body, bytes.size());
  std::uint64_t left = available;  // what the elements before this one leave, at the least
  for (const element& e : elements) {
    if (e.count != 0 && e.min_bytes != 0 && e.count > left / e.min_bytes)
      throw error(name + ": the PLY header declares " + std::to_string(e.count) + " " + e.name + " elements, but the " +
                  std::to_string(left) + " bytes left for them after the header hold at most " +
                  std::to_string(left / e.min_bytes) + " (a truncated file, or a wrong count)");
    left -= e.count * e.min_bytes;
    if (e.name == "vertex" && e.count > limits().vertices)
      throw error(name + ": " + std::to_string(e.count) + " vertices, more than the limit of " +
                  std::to_string(limits().vertices) + " " + raise_hint("vertices"));
    if (e.name == "face" && e.count > limits().triangles)
      throw error(name + ": " + std::to_string(e.count) + " faces, more than the limit of " +
                  std::to_string(limits().triangles) + " " + raise_hint("triangles"));
  }
}

ZRAKA_MESH_FILE_FN void check_gltf_json(std::string_view json, const std::string& name) {
  bool previous_is_mime_key = false;  // the last string was the key "mimeType"
  for (std::size_t i = 0; i < json.size(); ++i) {
    if (json[i] == ':') continue;
    if (json[i] != '"') {
      if (json[i] != ' ' && json[i] != '\n' && json[i] != '\r' && json[i] != '\t') previous_is_mime_key = false;
      continue;
    }
    std::string text;  // the decoded string (code points above 0x7f kept as a marker byte)
    for (++i; i < json.size() && json[i] != '"'; ++i) {
      if (json[i] != '\\' || i + 1 >= json.size()) {
        text += json[i];
        continue;
      }
      const char e = json[++i];
      if (e == 'u' && i + 4 < json.size()) {
        unsigned code = 0;
        const auto [p, ec] = std::from_chars(json.data() + i + 1, json.data() + i + 5, code, 16);
        text += (ec == std::errc() && p == json.data() + i + 5 && code < 0x80) ? char(code) : '\x80';
        i += 4;
      } else {
        text += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e == 'b' ? '\b' : e == 'f' ? '\f' : e;
      }
    }
    std::size_t k = i + 1;
    while (k < json.size() && (json[k] == ' ' || json[k] == '\n' || json[k] == '\r' || json[k] == '\t')) ++k;
    const bool is_key = k < json.size() && json[k] == ':';
    if (!is_key && previous_is_mime_key && text.find('/') == std::string::npos)
      throw error(name + ": an image's mimeType '" + text.substr(0, 40) + "' is not a type/subtype (such as image/png)");
    previous_is_mime_key = is_key && text == "mimeType";
  }
}

// A GLB's header and chunk lengths against the file's size (assimp allocates what they declare:
// 1.9 GB from a 1.5 kB file, found by fuzz_mesh), then its JSON chunk as check_gltf_json.
inline void check_glb(std::string_view bytes, const std::string& name) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t x = 0;
    for (std::size_t b = 0; b < 4; ++b) x |= std::uint32_t(std::uint8_t(bytes[at + b])) << (8 * b);
    return x;
  };
  if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF") return;  // assimp names what it is not
  if (u32(4) != 2) throw error(name + ": GLB version " + std::to_string(u32(4)) + "; zraka reads glTF 2.0");
  if (u32(8) != bytes.size())
    throw error(name + ": the GLB header declares " + std::to_string(u32(8)) + " bytes, the file has " +
                std::to_string(bytes.size()));
  std::size_t at = 12;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8) throw error(name + ": GLB chunk " + std::to_string(chunk) + " is cut short");
    const std::uint64_t length = u32(at);
    if (length > bytes.size() - at - 8)
      throw error(name + ": GLB chunk " + std::to_string(chunk) + " declares " + std::to_string(length) +
                  " bytes, but only " + std::to_string(bytes.size() - at - 8) + " follow");
    if (chunk == 0) {
      if (bytes.substr(at + 4, 4) != "JSON") throw error(name + ": the first GLB chunk is not JSON");
      check_gltf_json(bytes.substr(at + 8, length), name);
    }
    at += 8 + length;
  }
}

// assimp opens files through this: only regular files within limits().file_bytes (a glTF's
// .bin buffers too); the first refusal is kept for the error message.
class bounded_io_system : public Assimp::DefaultIOSystem {
 public:
  // assimp's own Exists opens the file: a FIFO without a writer would block it.
  bool Exists(const char* file) const override {
    struct stat st {};
    return ::stat(file, &st) == 0;
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    struct stat st {};
    if (::stat(file, &st) != 0) return nullptr;  // assimp says it cannot open it
    std::string why;
    if (!S_ISREG(st.st_mode)) why = std::string(file) + ": is " + file_kind(st.st_mode) + "; only regular files are read";
    else if (std::uint64_t(st.st_size) > limits().file_bytes)
      why = std::string(file) + ": the file size " + std::to_string(st.st_size) + " bytes is more than the limit of " +
            std::to_string(limits().file_bytes) + " " + raise_hint("file_bytes");
    if (!why.empty()) {
      if (refusal.empty()) refusal = why;
      return nullptr;
    }
    return Assimp::DefaultIOSystem::Open(file, mode);
  }
  std::string refusal;
};

inline std::string vector_text(double x, double y, double z) {
  std::ostringstream s;
  s << "(" << x << ", " << y << ", " << z << ")";
  return s.str();
}

// The one material of a glTF file as an albedo, or why not.
inline void base_colour_of(const aiScene& s, const std::filesystem::path& path, mesh_file_contents& out) {
  const std::string name = path.string();
  std::vector<unsigned> used;
  for (unsigned i = 0; i < s.mNumMeshes; ++i)
    if (std::find(used.begin(), used.end(), s.mMeshes[i]->mMaterialIndex) == used.end())
      used.push_back(s.mMeshes[i]->mMaterialIndex);
  if (used.size() != 1) {
    out.base_colour_problem = "the file's meshes use " + std::to_string(used.size()) +
                              " materials; material: from-file takes one";
    return;
  }
  if (used[0] >= s.mNumMaterials) {
    out.base_colour_problem = "a mesh's material index is out of range";
    return;
  }
  const aiMaterial& m = *s.mMaterials[used[0]];
  aiString mat_name;
  m.Get(AI_MATKEY_NAME, mat_name);
  const std::string label = "the material '" + std::string(mat_name.C_Str()) + "'";
  auto refuse = [&](const std::string& what) { out.base_colour_problem = label + " has " + what + ", which zraka does not map (only the base colour)"; };
  ai_real metallic = 0;
  if (m.Get(AI_MATKEY_METALLIC_FACTOR, metallic) == AI_SUCCESS && metallic > 0)
    return refuse("metallicFactor " + std::to_string(metallic) + " (a metal)");
  aiColor3D emissive(0, 0, 0);
  if (m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive) == AI_SUCCESS && (emissive.r > 0 || emissive.g > 0 || emissive.b > 0))
    return refuse("emissiveFactor " + vector_text(emissive.r, emissive.g, emissive.b));
  for (const auto& [type, what] : {std::pair{aiTextureType_EMISSIVE, "an emissiveTexture"},
                                   std::pair{aiTextureType_NORMALS, "a normalTexture"},
                                   std::pair{aiTextureType_DIFFUSE_ROUGHNESS, "a metallicRoughnessTexture"}})
    if (m.GetTextureCount(type) > 0) return refuse(what);
  ai_real transmission = 0;
  if (m.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission) == AI_SUCCESS && transmission > 0)
    return refuse("KHR_materials_transmission");
  aiColor4D factor(1, 1, 1, 1);
  if (m.Get(AI_MATKEY_BASE_COLOR, factor) != AI_SUCCESS) m.Get(AI_MATKEY_COLOR_DIFFUSE, factor);
  const rgb f(float(factor.r), float(factor.g), float(factor.b));
  for (int c = 0; c < 3; ++c)
    if (!(f[c] >= 0 && f[c] <= 1)) throw error(name + ": " + label + "'s baseColorFactor must be in [0, 1]");
  aiString tex;
  const aiTextureType type = m.GetTextureCount(aiTextureType_BASE_COLOR) > 0 ? aiTextureType_BASE_COLOR : aiTextureType_DIFFUSE;
  if (m.GetTextureCount(type) == 0) {
    out.base_colour = texture::solid(f);
    return;
  }
  unsigned uv_set = 0;
  aiTextureMapMode wrap[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
  m.GetTexture(type, 0, &tex, nullptr, &uv_set, nullptr, nullptr, wrap);
  if (uv_set != 0) return refuse("a baseColorTexture on texture coordinate set " + std::to_string(uv_set));
  if (wrap[0] != wrap[1] || (wrap[0] != aiTextureMapMode_Wrap && wrap[0] != aiTextureMapMode_Clamp))
    return refuse("a baseColorTexture sampler other than REPEAT or CLAMP_TO_EDGE on both axes");
  const std::string source = tex.C_Str();
  std::shared_ptr<image> img;
  std::string shown;
  if (const aiTexture* embedded = s.GetEmbeddedTexture(source.c_str())) {
    shown = name + " (embedded texture " + source + ")";
    if (embedded->mHeight != 0) throw error(shown + ": an uncompressed embedded texture; zraka reads PNG");
    const std::string format = embedded->achFormatHint;
    if (format != "png") throw error(shown + ": the texture is '" + format + "'; zraka reads PNG");
    img = std::make_shared<image>(parse_png_texture(
        std::string_view(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth), shown, true));
  } else {
    const std::filesystem::path file = path.parent_path() / source;
    shown = name + ": baseColorTexture '" + source + "'";
    try {
      img = std::make_shared<image>(load_texture_image(file, true));
    } catch (const error& e) {
      throw error(shown + ": " + e.what());
    }
  }
  for (rgb& p : img->pixels) p *= f;  // the albedo is factor times texel (glTF 2.0, 3.9.2)
  out.base_colour = texture::image_map(std::move(img), wrap[0] == aiTextureMapMode_Wrap, path.filename().string());
}

}  // namespace detail

ZRAKA_MESH_FILE_FN mesh_file_contents load_mesh_file(const std::filesystem::path& path) {
  const std::string name = path.string(), ext = path.extension().string();
  mesh_file_contents out;
  if (ext != ".ply" && ext != ".gltf" && ext != ".glb") {  // as before there were others: OBJ
    out.geometry = load_obj(path);
    out.base_colour_problem = "an OBJ's materials (mtllib) are not read";
    return out;
  }
  const std::string bytes = read_input_file(path);  // a regular file within the size limit
  if (bytes.empty()) throw error(name + ": the file is empty");
  if (ext == ".ply") detail::check_ply_counts(bytes, name);
  if (ext == ".gltf") detail::check_gltf_json(bytes, name);
  if (ext == ".glb") detail::check_glb(bytes, name);

  Assimp::Importer importer;
  auto* io = new detail::bounded_io_system;  // the importer owns it
  importer.SetIOHandler(io);
  // Only assimp's validation: Debian builds assimp with its assertions on, and its triangulation
  // aborts the program on some malformed files (a PLY with a wrong count), so the polygons are
  // fanned and the nodes' transforms applied here.
  const aiScene* s = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  if (!io->refusal.empty()) throw error(name + ": " + io->refusal);
  if (!s) throw error(name + ": assimp cannot read it: " + importer.GetErrorString());
  if ((s->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || s->mNumMeshes == 0 || !s->mRootNode) throw error(name + ": no meshes");

  // Every (mesh, transform) that the node tree places, without recursion (a deep tree cannot
  // overflow the stack); the counts are checked before any vertex is copied.
  struct placed {
    unsigned mesh;
    aiMatrix4x4 to_world;
  };
  std::vector<placed> parts;
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> todo{{s->mRootNode, s->mRootNode->mTransformation}};
  bool all_normals = true, all_uv = true;
  std::uint64_t vertices = 0, triangles = 0;
  while (!todo.empty()) {
    const auto [node, m] = todo.back();
    todo.pop_back();
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned i = node->mMeshes[k];
      if (i >= s->mNumMeshes) throw error(name + ": a node refers to mesh " + std::to_string(i) + " of " + std::to_string(s->mNumMeshes));
      const aiMesh& me = *s->mMeshes[i];
      all_normals = all_normals && me.HasNormals();
      all_uv = all_uv && me.HasTextureCoords(0);
      vertices += me.mNumVertices;
      for (unsigned f = 0; f < me.mNumFaces; ++f) triangles += me.mFaces[f].mNumIndices > 2 ? me.mFaces[f].mNumIndices - 2 : 0;
      if (vertices > limits().vertices)
        throw error(name + ": more than the limit of " + std::to_string(limits().vertices) + " vertices " + raise_hint("vertices"));
      if (triangles > limits().triangles)
        throw error(name + ": more than the limit of " + std::to_string(limits().triangles) + " triangles " + raise_hint("triangles"));
      parts.push_back({i, m});
    }
    if (parts.size() > limits().triangles) throw error(name + ": more mesh instances than the limit of triangles");
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      if (node->mChildren[c]) todo.push_back({node->mChildren[c], m * node->mChildren[c]->mTransformation});
  }

  mesh& g = out.geometry;
  for (const placed& pl : parts) {
    const aiMesh& m = *s->mMeshes[pl.mesh];
    const std::string part = s->mNumMeshes > 1 ? " (mesh " + std::to_string(pl.mesh) + ")" : "";
    const aiMatrix4x4& t = pl.to_world;
    const glm::dmat3 linear(t.a1, t.b1, t.c1, t.a2, t.b2, t.c2, t.a3, t.b3, t.c3);  // glm is column-major
    const vec3 offset(t.a4, t.b4, t.c4);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    const bool mirrored = glm::determinant(linear) < 0;  // keep the winding counter-clockwise
    const auto base = std::uint32_t(g.positions.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& p = m.mVertices[v];
      const vec3 q = linear * vec3(p.x, p.y, p.z) + offset;
      if (!is_finite(q) || glm::any(glm::greaterThan(abs3(q), vec3(max_coordinate))))
        throw error(name + part + ": vertex " + std::to_string(v) + " is " + detail::vector_text(p.x, p.y, p.z) +
                    (is_finite(vec3(p.x, p.y, p.z)) ? " and its node's transform puts it" : "") +
                    ", not finite within +-1e18");
      g.positions.push_back(q);
      if (all_normals) {
        const aiVector3D& n = m.mNormals[v];
        const vec3 nw = normal_matrix * vec3(n.x, n.y, n.z);
        if (!is_finite(nw)) throw error(name + part + ": the normal of vertex " + std::to_string(v) + " is not finite");
        g.normals.push_back(normalize_or_zero(nw));
      }
      if (all_uv) {
        const aiVector3D& uv = m.mTextureCoords[0][v];
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
          throw error(name + part + ": the texture coordinates of vertex " + std::to_string(v) + " are not finite");
        g.texcoords.push_back(vec2(uv.x, uv.y));
      }
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices < 3)
        throw error(name + part + ": face " + std::to_string(f) + " has " + std::to_string(face.mNumIndices) +
                    " corners (a point or a line has no surface; only triangles and polygons are rendered)");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= m.mNumVertices)
          throw error(name + part + ": face " + std::to_string(f) + " refers to vertex " +
                      std::to_string(face.mIndices[k]) + ", but there are " + std::to_string(m.mNumVertices));
      for (unsigned k = 2; k < face.mNumIndices; ++k) {  // a fan, as the OBJ reader makes
        std::array<std::uint32_t, 3> tri{base + face.mIndices[0], base + face.mIndices[k - 1], base + face.mIndices[k]};
        if (mirrored) std::swap(tri[1], tri[2]);
        g.triangles.push_back(tri);
      }
    }
  }
  if (g.triangles.empty()) throw error(name + ": no faces");
  if (ext == ".ply") out.base_colour_problem = "a PLY file has no material";
  else detail::base_colour_of(*s, path, out);
  return out;
}

}  // namespace zraka
#endif
