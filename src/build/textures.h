// Texture directives → render/ textures (pbrt-v3 names and defaults), and the image loading
// that image textures and environment maps share.
#pragma once

#include <memory>
#include <string>

#include "build/build_context.h"
#include "image/image_io.h"

namespace prism {

// Creates every Texture directive's texture into ctx.floatTextures / ctx.rgbTextures.
void BuildTextures(BuildContext &ctx);

TexturePtr Constant(RGB v);

// A texture-valued parameter ("Kd", "tex1", "amount", ...): a named texture or a value.
TexturePtr TextureParam(BuildContext &ctx, const ParamSet &ps, const std::string &name,
                        bool isFloat, RGB def);

// Reads (once per path and encoding) the image an entity's parameter `param` names, within the
// memory budget; errors point at that parameter.
std::shared_ptr<const Image> LoadSceneImage(BuildContext &ctx, const SceneEntity &entity,
                                            const std::string &file, ReadImageOptions::Encoding enc,
                                            const char *param);

}  // namespace prism
