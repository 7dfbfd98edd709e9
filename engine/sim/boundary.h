#pragma once
// Boundary particles (docs/SPH.md eq. (8)): the tank's floor and four walls (and its lid when the
// scene closes it) and
// every obstacle, sampled in `layers` layers on the solid side of each surface, never sparser than the
// fluid's spacing. Each particle is (x_b, V_cell): its position and the volume of the lattice cell it
// stands for, which caps its Akinci volume on the GPU (glsl/sim/boundary/compute_boundary_volume.comp
// replaces w with psi_b at start).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::scene { struct Scene; }

namespace ranryu::sim {

// Enough layers that a fluid particle touching a surface has a full kernel of boundary behind it:
// layers·spacing > support.
int boundary_layers(float spacing, float support);

// Boxes (the tank's shell and box obstacles) on cell-centred lattices whose pitch along each axis is
// the extent divided into ceil(extent / spacing) cells, so <= spacing: the outer layer lies half a pitch
// inside every face, edges and corners included. Spheres in concentric shells at R - (l + 1/2)·spacing,
// each a Fibonacci lattice with points 0.7 spacings apart, and a centre particle where the shells
// reach it.
std::vector<glm::vec4> sample_boundary(const scene::Scene& s, int layers);
// sample_boundary(s, layers).size(), without storing the samples.
std::size_t boundary_count(const scene::Scene& s, int layers);

// The obstacles as the integrate pass's projection reads them (glsl/sim/fluid/motion.glsl, storage
// block Obstacles): element 0 is (count, 0, 0, 0); then two vec4 an obstacle: a box as (min, 0),
// (max, 0); a sphere as (center, 1), (radius, 0, 0, 0); last, with a paddle (scene.paddle_radius > 0),
// the paddle as (center, 2), (radius, velocity), written parked: (paddle_park(s), 2), (0, 0, 0, 0).
std::vector<glm::vec4> obstacle_shapes(const scene::Scene& s);

// The paddle, a kinematic sphere of radius scene.paddle_radius that `ranryu run` drags through the
// liquid: its boundary particles are the last of sample_boundary() (after the obstacles), sampled as
// a sphere obstacle is, about the origin: paddle_offsets() gives them as (offset from the centre,
// V_cell). sim::Fluid::move_paddle() places them about the paddle's centre each frame it moves.
std::vector<glm::vec4> paddle_offsets(const scene::Scene& s, int layers);
// Where a paddle that is off waits: below the tank, farther than a kernel support from every fluid
// particle and wall particle (the neighbour grid clamps it into its bottom row of cells).
glm::vec3 paddle_park(const scene::Scene& s);
// The paddle's radius for a scene: a tenth of the tank's largest extent, at most 0.45 of its smallest
// (it fits between two walls), and never below 3 spacings (its boundary needs a kernel's depth).
float paddle_radius_for(const scene::Scene& s);

}  // namespace ranryu::sim
