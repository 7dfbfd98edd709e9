#pragma once
// Linked GL programs built from glsl/ files through the include step. All programs are built when
// their pass is constructed, at start-up; nothing compiles in the frame path.
//
// Shader storage blocks are bound by name, never by a number shared across the code base: at link
// every active storage block of a program gets its own slot (its block index), and a StorageSet
// names the buffers of a dispatch by block name. A dispatch binds every storage block of its program
// right before it (bind(set)): binding state is shared by all programs, so nothing may rely on a
// buffer bound for another program. Uniform blocks keep the fixed RANRYU_UBO_* points of
// shared/bindings.h: a handful of parameter blocks that every pass may read.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gl/objects.h"
#include "shader/source.h"

namespace ranryu::shader {

class Program;

// The storage buffers of one or more dispatches, by the block name the shaders declare. Holds no
// allocation (a fixed array of entries), so one is built on the stack per dispatch in the frame path.
// Names are string literals (the set keeps the views).
class StorageSet {
public:
    static constexpr std::size_t capacity = 32;
    StorageSet() = default;
    StorageSet(std::initializer_list<std::pair<std::string_view, const gl::Buffer*>> entries);

    // Adds (or replaces) the buffer of block `block`; a null or empty buffer is skipped.
    StorageSet& add(std::string_view block, const gl::Buffer& buffer);
    StorageSet& add(std::string_view block, const gl::Buffer* buffer) { return buffer ? add(block, *buffer) : *this; }
    // Binds [offset, offset + bytes) of `buffer` to block `block`.
    StorageSet& range(std::string_view block, const gl::Buffer& buffer, std::size_t offset, std::size_t bytes);
    StorageSet with(std::string_view block, const gl::Buffer& buffer) const { return StorageSet(*this).add(block, buffer); }
    // This set and every entry of `other` (other's win on equal names).
    StorageSet merged(const StorageSet& other) const;

    struct Entry {
        std::string_view block;
        GLuint buffer = 0;
        std::size_t offset = 0, bytes = 0;   // bytes 0: the whole buffer
    };
    const Entry* find(std::string_view block) const;
    std::size_t size() const { return count_; }

private:
    std::array<Entry, capacity> entries_{};
    std::size_t count_ = 0;
};

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

    // Binds each active storage block of this program to the buffer `set` names for it. Throws
    // ranryu::Error naming the program and the block when the set lacks one (the dispatch would read
    // whatever an earlier one left bound). Entries for blocks this program does not use are ignored.
    const Program& bind(const StorageSet& set) const;
    // The active storage blocks, in slot order, and one's slot (-1 when not active in this program).
    const std::vector<std::string>& storage_blocks() const { return blocks_; }
    int storage_slot(std::string_view block) const;

private:
    void assign_storage_slots();

    gl::Name<gl::DeleteProgram> name_;
    std::string label_;
    std::array<GLuint, 3> local_size_{0, 0, 0};
    std::vector<std::string> blocks_;   // active storage blocks; block i is bound at slot i
};

}  // namespace ranryu::shader
