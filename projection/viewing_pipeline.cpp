// SPDX-License-Identifier: Apache-2.0
// The viewing pipeline's step matrices (column-major GLM: m[column][row]).
#include "viewing_pipeline.h"

namespace overlayd {

glm::dmat4 ViewingPipeline::shear(const glm::dvec3 &cw)
{
    glm::dmat4 h(1.0);
    h[2][0] = -cw.x / cw.z;
    h[2][1] = -cw.y / cw.z;
    return h;
}

glm::dmat4 ViewingPipeline::scaleXY(double focal, double width, double height)
{
    glm::dmat4 s(1.0);
    s[0][0] = 2.0 * focal / width;
    s[1][1] = 2.0 * focal / height;
    return s;
}

glm::dmat4 ViewingPipeline::scaleFar(double far)
{
    glm::dmat4 s(1.0);
    s[0][0] = s[1][1] = s[2][2] = 1.0 / far;
    return s;
}

glm::dmat4 ViewingPipeline::perspective(double n)
{
    glm::dmat4 p(1.0);
    p[2][2] = -1.0 / (1.0 - n);
    p[3][2] = -n / (1.0 - n);
    p[2][3] = -1.0;
    p[3][3] = 0.0;
    return p;
}

glm::dmat4 ViewingPipeline::orthographic(double width, double height, double near, double far)
{
    glm::dmat4 scale(1.0);
    scale[0][0] = 2.0 / width;
    scale[1][1] = 2.0 / height;
    scale[2][2] = -1.0 / (far - near);
    glm::dmat4 toNear(1.0);
    toNear[3][2] = near;
    return scale * toNear;
}

glm::dmat4 ViewingPipeline::parallel(bool keepDepth)
{
    glm::dmat4 p(1.0);
    p[2][2] = keepDepth ? 1.0 : 0.0;
    return p;
}

glm::dmat4 ViewingPipeline::normalize()
{
    glm::dmat4 n(1.0);
    n[0][0] = n[1][1] = 0.5;
    n[3][0] = n[3][1] = 0.5;
    return n;
}

glm::dmat4 ViewingPipeline::rasterScale(double xres, double yres)
{
    glm::dmat4 s(1.0);
    s[0][0] = xres;
    s[1][1] = yres;
    return s;
}

glm::dmat4 ViewingPipeline::rasterTranslate(double posx, double posy)
{
    glm::dmat4 t(1.0);
    t[3][0] = posx;
    t[3][1] = posy;
    return t;
}

} // namespace overlayd
