#include "pipeline/viewport.h"

namespace rast {

ScreenMapping ScreenMapping::forState(const PipelineState& state) {
  if (state.positionSpace == PositionSpace::Window) return ScreenMapping{};
  const Viewport& vp = state.viewport;
  ScreenMapping m;
  // NDC y points up and window y down, hence the negative y scale.
  m.scale = {0.5 * vp.width, -0.5 * vp.height, 0.5};
  m.offset = {vp.x + 0.5 * vp.width, vp.y + 0.5 * vp.height, 0.5};
  return m;
}

ClipPlane ScreenMapping::windowAtLeast(int axis, double bound) const {
  ClipPlane p(0.0);
  p[axis] = scale[axis];
  p.w = offset[axis] - bound;
  return p;
}

ClipPlane ScreenMapping::windowAtMost(int axis, double bound) const {
  ClipPlane p(0.0);
  p[axis] = -scale[axis];
  p.w = bound - offset[axis];
  return p;
}

ClipPlanes ClipPlanes::forState(const PipelineState& state, const ScreenMapping& m) {
  const Viewport& vp = state.viewport;
  const double guard = state.format.guardBandPixels();
  ClipPlanes planes;
  planes.reject = {m.windowAtLeast(0, vp.x),          m.windowAtMost(0, vp.x + vp.width),
                   m.windowAtLeast(1, vp.y),          m.windowAtMost(1, vp.y + vp.height),
                   m.windowAtLeast(2, 0.0),           m.windowAtMost(2, 1.0)};
  planes.clip = {ClipPlane(0, 0, 0, 1),
                 m.windowAtLeast(2, 0.0), m.windowAtMost(2, 1.0),
                 m.windowAtLeast(0, -guard), m.windowAtMost(0, guard),
                 m.windowAtLeast(1, -guard), m.windowAtMost(1, guard)};
  return planes;
}

}  // namespace rast
