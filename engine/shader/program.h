#pragma once
// Linked GL programs built from glsl/ files through the include step. All programs are built when
// their pass is constructed, at start-up; nothing compiles in the frame path.
#include <array>
#include <string>
#include <string_view>

#include "gl/objects.h"
#include "shader/source.h"

namespace ranryu::shader {

class Program {
public:
    Program() = default;
    // A compute program from one .comp file. `defines` are "#define ..." lines (variants).
    static Program compute(const FileSource& src, const std::string& path, std::string_view defines = {});
    // A raster program from a vertex and a fragment file.
    static Program graphics(const FileSource& src, const std::string& vert, const std::string& frag,
                            std::string_view defines = {});

    GLuint id() const { return name_.id(); }
    const std::string& name() const { return label_; }
    void use() const { glUseProgram(id()); }

    // Compute programs: the workgroup size declared in the shader (GL_COMPUTE_WORK_GROUP_SIZE).
    std::array<GLuint, 3> local_size() const { return local_size_; }
    // Workgroups along x that cover `items` invocations (0 for 0: glDispatchCompute(0, …) is a no-op).
    GLuint groups_for(std::size_t items) const;
    // use() + glDispatchCompute over `items` along x.
    void dispatch(std::size_t items) const;

private:
    gl::Name<gl::DeleteProgram> name_;
    std::string label_;
    std::array<GLuint, 3> local_size_{0, 0, 0};
};

}  // namespace ranryu::shader
