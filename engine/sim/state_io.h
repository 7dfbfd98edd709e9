#pragma once
// What a simulation keeps from one frame to the next, written out and read back (frame/checkpoint.h:
// `record --checkpoint FILE` and `--resume FILE`). Each part that keeps state lists it once, in its
// persist(StateIo&), and the same list serves both directions, so a save and its load cannot drift
// apart. What a part recomputes before it reads it (the grid, the neighbour masks, a step's
// densities) need not be listed, but may be: the contract is that a pipeline built from the same
// scene and given the listed state runs on exactly as the one that wrote it.
#include <cstddef>
#include <string>
#include <type_traits>

#include "gl/objects.h"

namespace ranryu::sim {

class StateIo {
public:
    virtual ~StateIo() = default;
    // The whole of `buffer`, under a name unique in the checkpoint. Saving reads it back (it waits for
    // the GPU: the end of a run, never the frame path); loading replaces it, after checking that the
    // saved size is the buffer's and that its first `finite_vec4s` vec4s hold finite numbers only (a
    // part's positions or velocities, from which a run would fail only later, as an instability).
    virtual void buffer(const std::string& name, gl::Buffer& buffer, std::size_t finite_vec4s = 0) = 0;
    // `size` bytes of a CPU value, the same way.
    virtual void bytes(const std::string& name, void* data, std::size_t size) = 0;
    // Whether this reads a checkpoint back (a part may note that it was resumed).
    virtual bool loading() const = 0;
    // A part refuses what it was given, `why` its reason: throws InputError, naming the checkpoint
    // when loading (saving, write_checkpoint() names it).
    [[noreturn]] virtual void refuse(const std::string& why) = 0;
    template <class T>
    void value(const std::string& name, T& v) {
        static_assert(std::is_trivially_copyable_v<T>, "a CPU value is saved as its bytes");
        bytes(name, &v, sizeof v);
    }
};

}  // namespace ranryu::sim
