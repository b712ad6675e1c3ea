// Texture directives → render/ textures (pbrt-v3 names and defaults), and the image loading
// that image textures and environment maps share.
#pragma once

#include <memory>
#include <string>

#include "assembly/build_context.h"
#include "image/image_io.h"

namespace prism {

// Creates every Texture directive's texture into ctx.floatTextures / ctx.rgbTextures.
void BuildTextures(BuildContext &ctx);

TexturePtr Constant(RGB v);

// A texture-valued parameter ("Kd", "tex1", "amount", ...): a named texture or a value.
TexturePtr TextureParam(BuildContext &ctx, const ParamSet &ps, const std::string &name,
                        bool isFloat, RGB def);

// The glTF texture-coordinate parameters of a map `name` (Prism extensions the glTF reader
// writes): "float <name>transform" [offset.u offset.v rotation scale.u scale.v]
// (KHR_texture_transform) and "integer <name>texcoord" 1 (reads TEXCOORD_1), each read from
// the ParamSet that has it (a shape's own, else the material's: `primary` then `fallback`).
// Returns `t` wrapped as they ask. Throws SceneError for a transform without 5 values or a
// set other than 0 and 1.
TexturePtr WithTexCoordParams(TexturePtr t, const ParamSet *primary, const ParamSet &fallback,
                              const std::string &name);

// The image file `file` (named by parameter `param` of `entity`) as a texture of the (u, v) of
// the surface it lies on, looked up as pbrt-v4 looks up an area light's image: bilinear,
// clamped at the edges, v = 0 on the image's bottom row (as an imagemap texture's), 8-bit
// files decoded from sRGB. Errors point at `param`.
TexturePtr ImageOnSurface(BuildContext &ctx, const SceneEntity &entity, const std::string &file,
                          const char *param);

// Reads (once per path and encoding) the image an entity's parameter `param` names, within the
// memory budget; errors point at that parameter.
std::shared_ptr<const Image> LoadSceneImage(BuildContext &ctx, const SceneEntity &entity,
                                            const std::string &file, ReadImageOptions::Encoding enc,
                                            const char *param);

}  // namespace prism
