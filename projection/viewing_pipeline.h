// SPDX-License-Identifier: Apache-2.0
// The classic viewing pipeline (PRP/VPN/VUP, window, viewport), one matrix per step, as its textbook derivation
// composes it (with the derivation's sign error corrected).
//
// T_camera = T_raster S_raster N P_parallel P_persp S_far S_xy H R T. Projection::window() composes
// P_persp S_far S_xy H from these; tests check each step against the derivation's worked mappings.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace overlayd {

// One static function per step, named as the derivation names it.
struct ViewingPipeline {
    // H: shears so that the window centre cw (camera coordinates, cw.z < 0) lies on the -Z axis.
    static glm::dmat4 shear(const glm::dvec3 &cw);
    // S_xy: scales x, y so that the window edges (full width, height at distance focal) open at 45 degrees.
    static glm::dmat4 scaleXY(double focal, double width, double height);
    // S_far: scales uniformly so that the far plane lands at z = -1.
    static glm::dmat4 scaleFar(double far);
    // P_persp with n = near / far: maps the canonical frustum to [-1,1]^2 x [0,1], near -> 0, far -> 1.
    // The derivation prints the third row as (0, 0, 1/(1-n), n/(1-n)), which sends near -> 0 but far -> -1, against
    // its own stated box [0, 1]; we negate that row so that depth grows away from the camera.
    static glm::dmat4 perspective(double n);
    // P_o = S_xyz T_near for a centred width x height window; the same sign correction applies to its z scale
    // (the derivation's 1/(far-near) sends the far plane to -1).
    static glm::dmat4 orthographic(double width, double height, double near, double far);
    // P_parallel: drops z (keepDepth = false) or keeps it as an attribute for depth testing.
    static glm::dmat4 parallel(bool keepDepth);
    // N: [-1,1]^2 -> [0,1]^2.
    static glm::dmat4 normalize();
    // S_raster and T_raster: [0,1]^2 -> pixel corners [0,xres] x [0,yres], then the window offset.
    static glm::dmat4 rasterScale(double xres, double yres);
    static glm::dmat4 rasterTranslate(double posx, double posy);
};

} // namespace overlayd
