// MakeNamedMedium directives → RenderScene::media (pbrt-v3 "homogeneous" and "heterogeneous",
// with pbrt's "preset" table), the camera's medium, and the MediumInterface of each shape.
#pragma once

#include "assembly/build_context.h"

namespace prism {

// Every named medium, in directive order (SceneDescription::media indices stay valid), and the
// camera's medium. Errors (at the parameter): unknown type, negative coefficients, a density
// grid whose size is not nx*ny*nz.
void BuildMedia(BuildContext &ctx);

// Warns when the scene has media but its integrator ("path", "directlighting") ignores them.
void WarnIgnoredMedia(BuildContext &ctx);

// Copies the shape's MediumInterface into its ShapeInfo and, for a transition (different inside
// and outside media), turns on Effect::Media with the MediumInterface directive as the reason.
void NoteShapeMedia(BuildContext &ctx, const ShapeDesc &s, ShapeInfo *info);

}  // namespace prism
