#include "shader/program.h"

#include <algorithm>
#include <regex>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace ranryu::shader {
namespace {

std::string info_log(GLuint object, bool is_program) {
    GLint length = 0;
    if (is_program) glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(length > 0 ? length : 1), '\0');
    if (is_program) glGetProgramInfoLog(object, length, nullptr, log.data());
    else glGetShaderInfoLog(object, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

// The first "file:line: ..." of an annotated log, for the one-line summary.
std::string first_error(const std::string& annotated, const std::string& fallback) {
    static const std::regex located(R"(([^\s:]+:\d+):(\d+:)?\s*(error)?:?\s*([^\n]*))");
    std::smatch m;
    std::istringstream lines(annotated);
    for (std::string line; std::getline(lines, line);)
        if (line.find("error") != std::string::npos && std::regex_search(line, m, located))
            return m[1].str() + ": " + m[4].str();
    return fallback;
}

// The lines of an annotated log worth showing under its summary: its errors (a driver also lists
// warnings, a dozen of them for one mistake on Mesa), at most kShown, then how many more it had; the
// first lines where none says "error" (another driver's wording).
std::string error_lines(const std::string& annotated) {
    constexpr std::size_t kShown = 4;
    std::vector<std::string> all, errors;
    std::istringstream lines(annotated);
    for (std::string line; std::getline(lines, line);) {
        if (line.empty()) continue;
        all.push_back(line);
        if (line.find("error") != std::string::npos) errors.push_back(line);
    }
    const std::vector<std::string>& shown = errors.empty() ? all : errors;
    std::string out;
    for (std::size_t k = 0; k < std::min(shown.size(), kShown); ++k) out += (k ? "\n" : "") + shown[k];
    if (all.size() > std::min(shown.size(), kShown))
        out += "\n(" + std::to_string(all.size() - std::min(shown.size(), kShown)) + " more lines of the driver's log, warnings among them)";
    return out;
}

gl::Name<gl::DeleteShader> compile(GLenum stage, const FileSource& src, const std::string& path,
                                   std::string_view defines) {
    const Preprocessed pre = preprocess(src, path, defines);
    gl::Name<gl::DeleteShader> shader(glCreateShader(stage));
    const char* text = pre.text.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = annotate_log(info_log(shader.id(), false), pre.files);
        throw Error("shader " + first_error(log, path + ": failed to compile") + "\n" + error_lines(log));
    }
    return shader;
}

gl::Name<gl::DeleteProgram> link(const std::vector<GLuint>& shaders, const std::string& label) {
    gl::Name<gl::DeleteProgram> program(glCreateProgram());
    for (GLuint s : shaders) glAttachShader(program.id(), s);
    glLinkProgram(program.id());
    for (GLuint s : shaders) glDetachShader(program.id(), s);
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) throw Error("shader program " + label + ": failed to link\n" + info_log(program.id(), true));
    gl::label(GL_PROGRAM, program.id(), label);
    return program;
}

}  // namespace

StorageSet::StorageSet(std::initializer_list<std::pair<std::string_view, const gl::Buffer*>> entries) {
    for (const auto& [block, buffer] : entries) add(block, buffer);
}

StorageSet& StorageSet::add(std::string_view block, const gl::Buffer& buffer) {
    if (!buffer.id()) return *this;
    return range(block, buffer, 0, 0);
}

StorageSet& StorageSet::range(std::string_view block, const gl::Buffer& buffer, std::size_t offset, std::size_t bytes) {
    for (std::size_t k = 0; k < count_; ++k)
        if (entries_[k].block == block) {
            entries_[k] = Entry{block, buffer.id(), offset, bytes};
            return *this;
        }
    if (count_ == capacity) throw Error("StorageSet: more than " + std::to_string(capacity) + " blocks (adding " + std::string(block) + ")");
    entries_[count_++] = Entry{block, buffer.id(), offset, bytes};
    return *this;
}

StorageSet StorageSet::merged(const StorageSet& other) const {
    StorageSet out(*this);
    for (std::size_t k = 0; k < other.count_; ++k) {
        const Entry& e = other.entries_[k];
        bool replaced = false;
        for (std::size_t m = 0; m < out.count_ && !replaced; ++m)
            if (out.entries_[m].block == e.block) out.entries_[m] = e, replaced = true;
        if (!replaced) {
            if (out.count_ == capacity) throw Error("StorageSet: more than " + std::to_string(capacity) + " blocks");
            out.entries_[out.count_++] = e;
        }
    }
    return out;
}

const StorageSet::Entry* StorageSet::find(std::string_view block) const {
    for (std::size_t k = 0; k < count_; ++k)
        if (entries_[k].block == block) return &entries_[k];
    return nullptr;
}

void Program::assign_storage_slots() {
    GLint count = 0;
    glGetProgramInterfaceiv(id(), GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &count);
    blocks_.clear();
    for (GLint i = 0; i < count; ++i) {
        GLint length = 0;
        const GLenum property = GL_NAME_LENGTH;
        glGetProgramResourceiv(id(), GL_SHADER_STORAGE_BLOCK, GLuint(i), 1, &property, 1, nullptr, &length);
        std::string name(std::size_t(std::max(length, 1)), '\0');
        glGetProgramResourceName(id(), GL_SHADER_STORAGE_BLOCK, GLuint(i), length, nullptr, name.data());
        while (!name.empty() && name.back() == '\0') name.pop_back();
        glShaderStorageBlockBinding(id(), GLuint(i), GLuint(i));
        blocks_.push_back(std::move(name));
    }
}

int Program::storage_slot(std::string_view block) const {
    for (std::size_t k = 0; k < blocks_.size(); ++k)
        if (blocks_[k] == block) return int(k);
    return -1;
}

const Program& Program::bind(const StorageSet& set) const {
    for (std::size_t k = 0; k < blocks_.size(); ++k) {
        const StorageSet::Entry* e = set.find(blocks_[k]);
        if (!e) throw Error("shader program " + label_ + ": no buffer for its storage block " + blocks_[k]);
        if (e->bytes) glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(k), e->buffer, GLintptr(e->offset), GLsizeiptr(e->bytes));
        else glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(k), e->buffer);
    }
    return *this;
}

Program Program::compute(const FileSource& src, const std::string& path, std::string_view defines) {
    Program p;
    auto cs = compile(GL_COMPUTE_SHADER, src, path, defines);
    p.label_ = path;
    p.name_ = link({cs.id()}, path);
    p.assign_storage_slots();
    GLint size[3] = {0, 0, 0};
    glGetProgramiv(p.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
    p.local_size_ = {GLuint(size[0]), GLuint(size[1]), GLuint(size[2])};
    return p;
}

Program Program::graphics(const FileSource& src, const std::string& vert, const std::string& frag,
                          std::string_view defines) {
    Program p;
    auto vs = compile(GL_VERTEX_SHADER, src, vert, defines);
    auto fs = compile(GL_FRAGMENT_SHADER, src, frag, defines);
    p.label_ = vert + "+" + frag;
    p.name_ = link({vs.id(), fs.id()}, p.label_);
    p.assign_storage_slots();
    return p;
}

GLuint Program::groups_for(std::size_t items) const {
    const std::size_t per = local_size_[0] ? local_size_[0] : 1;
    return GLuint((items + per - 1) / per);
}

void Program::dispatch(std::size_t items) const {
    use();
    glDispatchCompute(groups_for(items), 1, 1);
}

}  // namespace ranryu::shader
