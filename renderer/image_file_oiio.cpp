// read_image through OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <stdexcept>

#include "image_file.h"

namespace softtrace {

ImageFile read_image(const std::string& path) {
  using namespace OIIO;
  auto in = ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": cannot read the image: " + OIIO::geterror());
  const ImageSpec& spec = in->spec();
  if (spec.deep) throw std::runtime_error(path + ": deep images are not supported");
  if (spec.depth != 1) throw std::runtime_error(path + ": volume images are not supported");

  ImageFile f;
  // Windows relative to the display window's origin, which our own images keep at (0, 0).
  f.full_width = spec.full_width;
  f.full_height = spec.full_height;
  f.x0 = spec.x - spec.full_x;
  f.y0 = spec.y - spec.full_y;
  f.width = spec.width;
  f.height = spec.height;
  f.channels = spec.channelnames;
  for (const ParamValue& p : spec.extra_attribs)
    if (p.type() == TypeDesc::STRING) f.attributes[p.name().string()] = p.get_string();

  f.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, f.pixels.data()))
    throw std::runtime_error(path + ": cannot read the pixels: " + in->geterror());
  return f;
}

}  // namespace softtrace
