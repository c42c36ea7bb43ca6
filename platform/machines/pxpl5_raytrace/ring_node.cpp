// The sizes of pxpl5-raytrace's messages on the ring, and their parameters, each named once.
#include "platform/machines/pxpl5_raytrace/ring_node.hpp"

#include "modules/module_params.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

const char* const kNoFormats = "assumption: the seed gives no message formats (note 004 A)";

const modules::CountParam kControl(
    {.name = "control_bytes",
     .default_value = "16",
     .min = "1",
     .max = "65536",
     .unit = "bytes",
     .description = "Bytes of a control message on the ring (frame start, request, assignment, "
                    "frame done)",
     .source = kNoFormats});
const modules::CountParam kSample(
    {.name = "sample_bytes",
     .default_value = "8",
     .min = "1",
     .max = "65536",
     .unit = "bytes",
     .description = "Bytes of one sample on the ring (samples and band messages)",
     .source = "assumption: 24-bit colour, depth and flags"});
const modules::CountParam kPixel({.name = "pixel_bytes",
                                  .default_value = "4",
                                  .min = "1",
                                  .max = "65536",
                                  .unit = "bytes",
                                  .description = "Bytes of one display pixel on the ring",
                                  .source = "assumption: 24-bit colour and a byte of alpha"});
const modules::CountParam kHeader(
    {.name = "header_bytes",
     .default_value = "16",
     .min = "0",
     .max = "65536",
     .unit = "bytes",
     .description = "Bytes of header on a samples, band or pixels message",
     .source = "assumption"});
/// Where they are declared and read.
const char* const kPath = "wire";

}  // namespace

std::uint64_t WireSizes::bytes(const Message& m) const {
  switch (m.kind) {
    case Kind::kSamples:
    case Kind::kBand:
      return header + sample * m.samples.size();
    case Kind::kPixels:
      return header + pixel * m.samples.size();
    default:
      return control;
  }
}

void WireSizes::declare_params(params::ParamRegistry& r) {
  const modules::ParamDecls wire(r, kPath, false);
  for (const auto* p : {&kControl, &kSample, &kPixel, &kHeader}) wire.add(*p);
}

WireSizes WireSizes::read(const params::ParamRegistry& r) {
  const modules::ModuleParams wire(r, kPath);
  return {.control = wire.get(kControl),
          .sample = wire.get(kSample),
          .pixel = wire.get(kPixel),
          .header = wire.get(kHeader)};
}

}  // namespace rtsim::platform::pxpl5
