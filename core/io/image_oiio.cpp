// libmvr_image_oiio.so: OpenImageIO behind mvr_image.h's functions, as a
// table the C front (image_io.c) loads with dlopen() the first time a call
// needs it (image_internal.h says why). No exception leaves this file; every
// failure becomes an mvr_result with a message. The front has checked the
// arguments and, for encoded bytes, the signature, MIME type and PNG framing;
// the checks here stay so that the module answers alone as mvr_image did.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/half.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "image_internal.h"

namespace {

using namespace OIIO;

mvr_result fail(mvr_error *error, mvr_result r, const std::string &msg)
{
    if (error) {
        error->result = r;
        std::snprintf(error->message, sizeof error->message, "%s", msg.c_str());
    }
    return r;
}

// Formats mvr decodes, told apart by their signatures (PNG: ISO/IEC 15948,
// 5.2; JPEG: ISO/IEC 10918-1 SOI marker FF D8 FF; WebP: RIFF....WEBP). The
// OpenImageIO reader is named by the signature, never by a file name, so a
// URI's extension cannot pick a decoder (a video plugin, say).
struct image_format {
    const char *name;        /* mvr_image_header.format */
    const char *oiio_name;   /* a name OpenImageIO picks the reader by */
    const char *mime;
};

const image_format *format_of_bytes(const unsigned char *p, size_t n)
{
    static const image_format png = {"png", "image.png", "image/png"};
    static const image_format jpeg = {"jpeg", "image.jpg", "image/jpeg"};
    static const image_format webp = {"webp", "image.webp", "image/webp"};
    static const unsigned char png_sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    if (n >= 8 && std::memcmp(p, png_sig, 8) == 0)
        return &png;
    if (n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF)
        return &jpeg;
    if (n >= 12 && std::memcmp(p, "RIFF", 4) == 0 && std::memcmp(p + 8, "WEBP", 4) == 0)
        return &webp;
    return nullptr;
}

// The declared MIME type (glTF 2.0, 5.19: image/jpeg or image/png; WebP by
// EXT_texture_webp) must name what the bytes are.
bool mime_agrees(const char *mime, const image_format *f)
{
    if (!mime || !*mime)
        return true;
    std::string m = mime;
    if (m == "image/jpg")
        m = "image/jpeg"; /* a common misspelling, same format */
    return m == f->mime;
}

// Whether this OpenImageIO build reads the format (WebP is optional in
// OpenImageIO's builds; Debian 12's has it): its input_format_list.
bool has_reader(const image_format *f)
{
    std::string list = std::string(OIIO::get_string_attribute("input_format_list"));
    std::string want = f->oiio_name + 6;   /* "image.webp" -> "webp" */
    if (want == "jpg")
        want = "jpeg";
    size_t at = 0;
    while (at <= list.size()) {
        size_t end = list.find(',', at);
        if (end == std::string::npos)
            end = list.size();
        if (list.compare(at, end - at, want) == 0)
            return true;
        at = end + 1;
    }
    return false;
}

// At most 80 characters of a value that came from a file, for a message.
std::string short_value(const char *v)
{
    std::string s = v ? v : "";
    if (s.size() > 80)
        s = s.substr(0, 80) + "...";
    for (char &c : s)
        if (static_cast<unsigned char>(c) < 0x20)
            c = '?';
    return "'" + s + "'";
}

// PNG framing (ISO/IEC 15948, 5.3): the signature, then chunks of length +
// type + data + CRC, the last one IEND, all inside the bytes. Checked before
// decoding: OpenImageIO 2.4's PNG reader leaks when libpng longjmps out of a
// read past the end, and a truncated file is refused here with a clear
// message instead. (This reads chunk lengths; it decodes nothing.)
bool png_framing_ok(const unsigned char *p, size_t n, std::string *why)
{
    size_t at = 8;
    while (at + 12 <= n) {
        uint32_t len = uint32_t(p[at]) << 24 | uint32_t(p[at + 1]) << 16 | uint32_t(p[at + 2]) << 8 | p[at + 3];
        if (len > 0x7FFFFFFFu || uint64_t(at) + 12 + len > n) {
            *why = "PNG chunk at byte " + std::to_string(at) + " runs past the end of the data (truncated?)";
            return false;
        }
        if (std::memcmp(p + at + 4, "IEND", 4) == 0)
            return true;
        at += 12 + size_t(len);
    }
    *why = "PNG has no IEND chunk (truncated?)";
    return false;
}

ImageSpec rgba_spec(const mvr_image_view *v, TypeDesc type)
{
    return ImageSpec(int(v->width), int(v->height), 4, type);
}

// The view's pixels as an ImageBuf (rows top first), float for comparisons.
bool to_buf(const mvr_image_view *v, ImageBuf &out, bool as_float)
{
    if (!v || !v->pixels || v->width == 0 || v->height == 0)
        return false;
    TypeDesc src = v->type == MVR_PIXEL_F32 ? TypeDesc::FLOAT : TypeDesc::UINT8;
    ImageBuf buf(rgba_spec(v, as_float ? TypeDesc::FLOAT : src));
    size_t px = v->type == MVR_PIXEL_F32 ? 16 : 4;
    stride_t ystride = stride_t(v->width * px);
    const char *first = static_cast<const char *>(v->pixels);
    if (v->bottom_up) {
        first += size_t(v->height - 1) * size_t(ystride);
        ystride = -ystride;
    }
    if (!buf.set_pixels(ROI(0, int(v->width), 0, int(v->height), 0, 1, 0, 4), src, first, AutoStride, ystride))
        return false;
    out.swap(buf);
    return true;
}

}  // namespace

// The widest channel of the file, in bytes (EXR channels may differ).
static uint32_t native_channel_bytes(const ImageSpec &spec)
{
    size_t widest = spec.format.size();
    for (const TypeDesc &t : spec.channelformats)
        widest = std::max(widest, t.size());
    return uint32_t(widest);
}

// What read_rgba holds at its peak for an opened image, from its header: the
// pixels as read_image delivers them (every stored channel, in the asked-for
// type) and the RGBA result, plus what the decoders hold besides:
//  - a file stored in another type than the one asked for: OpenImageIO reads
//    its own type and converts (charged as a whole copy, the most it holds);
//  - WebP: OpenImageIO 2.4's reader decodes the whole image into its own RGBA8
//    buffer before handing out any scanline.
// (A progressive JPEG's coefficients are found and added by the front.)
static uint64_t decode_cost(ImageInput *in, mvr_pixel_type type)
{
    const ImageSpec &spec = in->spec();
    uint64_t pixels = mvr_image_mul(uint64_t(std::max(spec.width, 0)), uint64_t(std::max(spec.height, 0)));
    uint64_t nc = uint64_t(std::max(spec.nchannels, 0));
    uint64_t out_bytes = type == MVR_PIXEL_F32 ? 4 : 1;
    uint64_t samples = mvr_image_mul(pixels, nc);
    uint64_t cost = mvr_image_add(mvr_image_mul(samples, out_bytes), mvr_image_mul(pixels, 4 * out_bytes));
    TypeDesc want = type == MVR_PIXEL_F32 ? TypeDesc::FLOAT : TypeDesc::UINT8;
    bool converts = spec.format != want;
    for (const TypeDesc &t : spec.channelformats)
        converts = converts || t != want;
    if (converts)
        cost = mvr_image_add(cost, mvr_image_mul(samples, native_channel_bytes(spec)));
    if (std::string(in->format_name()) == "webp")
        cost = mvr_image_add(cost, mvr_image_mul(pixels, 4));
    return cost;
}

// Reads an opened ImageInput into RGBA of the given type, refused before
// anything is allocated where decode_cost is over the budget.
static mvr_result read_rgba(ImageInput *in, mvr_pixel_type type, uint32_t max_dimension, uint64_t budget,
                            uint64_t held, const std::string &what, mvr_image_data *out, mvr_error *error)
{
    const ImageSpec &spec = in->spec();
    uint32_t cap = max_dimension ? max_dimension : 16384;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || uint32_t(spec.width) > cap ||
        uint32_t(spec.height) > cap || spec.depth > 1)
        return fail(error, MVR_ERROR_INVALID_ASSET,
                    what + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        " is not within 1.." + std::to_string(cap));
    uint64_t needed = mvr_image_add(decode_cost(in, type), held);
    if (needed > budget)
        return mvr_image_over_budget(error, what.c_str(), uint32_t(spec.width), uint32_t(spec.height),
                                     uint32_t(spec.nchannels), native_channel_bytes(spec), needed, budget);
    int nc = spec.nchannels;
    size_t pixels = size_t(spec.width) * size_t(spec.height);
    TypeDesc t = type == MVR_PIXEL_F32 ? TypeDesc::FLOAT : TypeDesc::UINT8;
    size_t bytes_per = type == MVR_PIXEL_F32 ? 4 : 1;
    std::vector<unsigned char> raw(pixels * size_t(nc) * bytes_per);
    if (!in->read_image(0, 0, 0, nc, t, raw.data()))
        return fail(error, MVR_ERROR_INVALID_ASSET, what + ": " + in->geterror());
    void *rgba = std::malloc(pixels * 4 * bytes_per);
    if (!rgba)
        return fail(error, MVR_ERROR_OUT_OF_MEMORY, what + ": out of memory");
    // expand gray, gray-alpha, RGB; keep the first four channels of more
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 4; ++c) {
            int src = nc == 1 ? 0 : nc == 2 ? (c < 3 ? 0 : 1) : c;
            bool have = (nc == 1 || nc == 3) ? c < 3 : true;
            if (type == MVR_PIXEL_F32) {
                const float *r = reinterpret_cast<const float *>(raw.data());
                static_cast<float *>(rgba)[i * 4 + size_t(c)] = have && src < nc ? r[i * size_t(nc) + size_t(src)] : 1.0f;
            } else {
                static_cast<unsigned char *>(rgba)[i * 4 + size_t(c)] =
                    have && src < nc ? raw[i * size_t(nc) + size_t(src)] : 255;
            }
        }
    }
    out->width = uint32_t(spec.width);
    out->height = uint32_t(spec.height);
    out->type = type;
    out->pixels = rgba;
    return MVR_OK;
}

namespace {

// Opens the reader the signature names, after the checks every caller needs,
// and hands it to use(in, format); exceptions become results named by who.
template <typename Use>
mvr_result with_encoded(const void *data, size_t size, const char *mime, const char *who, mvr_error *error, Use use)
{
    try {
        const auto *bytes = static_cast<const unsigned char *>(data);
        const image_format *f = format_of_bytes(bytes, size);
        if (!f)
            return fail(error, MVR_ERROR_UNSUPPORTED,
                        std::string(who) + ": the bytes are not PNG, JPEG or WebP (declared " +
                            (mime && *mime ? short_value(mime) : std::string("no mimeType")) + ")");
        if (!mime_agrees(mime, f))
            return fail(error, MVR_ERROR_INVALID_ASSET,
                        std::string(who) + ": mimeType " + short_value(mime) + " but the bytes are " + f->name);
        if (!has_reader(f))
            return fail(error, MVR_ERROR_UNSUPPORTED,
                        std::string(who) + ": this OpenImageIO build has no " + f->name + " reader");
        std::string why;
        if (std::strcmp(f->name, "png") == 0 && !png_framing_ok(bytes, size, &why))
            return fail(error, MVR_ERROR_INVALID_ASSET, std::string(who) + ": " + why);
        Filesystem::IOMemReader mem(data, size);
        auto in = ImageInput::open(f->oiio_name, nullptr, &mem);
        if (!in)
            return fail(error, MVR_ERROR_INVALID_ASSET, std::string(who) + ": " + short_value(OIIO::geterror().c_str()));
        return use(in.get(), f);
    } catch (const std::exception &e) {
        return fail(error, MVR_ERROR_INVALID_ASSET, std::string(who) + ": " + e.what());
    } catch (...) {
        return fail(error, MVR_ERROR_INTERNAL, std::string(who) + ": unknown exception");
    }
}

}  // namespace

static mvr_result oiio_probe(const void *data, size_t size, const char *mime_type, mvr_image_header *out,
                                      mvr_error *error)
{
    if (!out || !data || size == 0)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_probe: no data");
    std::memset(out, 0, sizeof *out);
    return with_encoded(data, size, mime_type, "mvr_image_probe", error, [&](ImageInput *in, const image_format *f) {
        const ImageSpec &spec = in->spec();
        if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
            return fail(error, MVR_ERROR_INVALID_ASSET, "mvr_image_probe: the header has no valid size");
        out->width = uint32_t(spec.width);
        out->height = uint32_t(spec.height);
        out->channels = uint32_t(spec.nchannels);
        out->format = f->name;
        return MVR_OK;
    });
}

static mvr_result oiio_decode_cost(const void *data, size_t size, const char *mime_type, uint64_t *out_bytes,
                                   mvr_error *error)
{
    if (!out_bytes || !data || size == 0)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_decode_cost: no data");
    *out_bytes = 0;
    return with_encoded(data, size, mime_type, "mvr_image_decode_cost", error,
                        [&](ImageInput *in, const image_format *) {
                            *out_bytes = decode_cost(in, MVR_PIXEL_U8);
                            return MVR_OK;
                        });
}

static mvr_result oiio_decode(const void *data, size_t size, const char *mime_type, uint32_t max_dimension,
                              uint64_t budget, uint64_t held, mvr_image_data *out, mvr_error *error)
{
    if (!out || !data || size == 0)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_decode: no data");
    std::memset(out, 0, sizeof *out);
    return with_encoded(data, size, mime_type, "mvr_image_decode", error, [&](ImageInput *in, const image_format *) {
        return read_rgba(in, MVR_PIXEL_U8, max_dimension, budget, held, "mvr_image_decode", out, error);
    });
}

static mvr_result oiio_read(const char *path, mvr_pixel_type type, uint64_t budget, uint64_t held,
                            mvr_image_data *out, mvr_error *error)
{
    if (!path || !out)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_read: NULL argument");
    std::memset(out, 0, sizeof *out);
    try {
        auto in = ImageInput::open(path);
        if (!in)
            return fail(error, MVR_ERROR_IO, std::string("mvr_image_read(") + path + "): " + OIIO::geterror());
        return read_rgba(in.get(), type, 0, budget, held, std::string("mvr_image_read(") + path + ")", out, error);
    } catch (const std::exception &e) {
        return fail(error, MVR_ERROR_IO, std::string("mvr_image_read: ") + e.what());
    } catch (...) {
        return fail(error, MVR_ERROR_INTERNAL, "mvr_image_read: unknown exception");
    }
}

static float srgb_decode(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

static mvr_result oiio_write(const char *path, const mvr_image_view *image, mvr_error *error)
{
    if (!path || !image || !image->pixels || image->width == 0 || image->height == 0)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_write: NULL or empty image");
    try {
        std::string p = path;
        std::string ext = p.size() > 4 ? p.substr(p.size() - 4) : "";
        for (char &c : ext)
            c = char(std::tolower(static_cast<unsigned char>(c)));
        bool exr = ext == ".exr";
        if (!exr && ext != ".png")
            return fail(error, MVR_ERROR_INVALID_ARGUMENT,
                        std::string("mvr_image_write(") + path + "): the name must end in .png or .exr");
        ImageBuf buf;
        if (!to_buf(image, buf, exr))
            return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_write: bad pixels");
        if (exr && image->type == MVR_PIXEL_U8) {
            // 8-bit input is sRGB-encoded; EXR holds linear values
            for (ImageBuf::Iterator<float> it(buf); !it.done(); ++it)
                for (int c = 0; c < 3; ++c)
                    it[c] = srgb_decode(it[c]);
        }
        ImageSpec spec = buf.spec();
        spec.set_format(exr ? TypeDesc::HALF : TypeDesc::UINT8);
        if (!exr)
            spec.attribute("oiio:ColorSpace", "sRGB");
        auto out = ImageOutput::create(p);
        if (!out || !out->open(p, spec))
            return fail(error, MVR_ERROR_IO,
                        std::string("mvr_image_write(") + path + "): " + (out ? out->geterror() : OIIO::geterror()));
        bool ok = buf.write(out.get());
        std::string err = ok ? "" : buf.geterror();
        if (!out->close() || !ok)
            return fail(error, MVR_ERROR_IO, std::string("mvr_image_write(") + path + "): " + err + out->geterror());
        return MVR_OK;
    } catch (const std::exception &e) {
        return fail(error, MVR_ERROR_IO, std::string("mvr_image_write: ") + e.what());
    } catch (...) {
        return fail(error, MVR_ERROR_INTERNAL, "mvr_image_write: unknown exception");
    }
}

// How a channel type is stored in an EXR (mvr_image.h): OpenEXR has HALF,
// FLOAT and UINT (32-bit) pixel types, so 16-bit integers go to FLOAT, exact.
static TypeDesc exr_type(mvr_channel_type t)
{
    switch (t) {
    case MVR_CHANNEL_U8:
    case MVR_CHANNEL_F16: return TypeDesc::HALF;
    case MVR_CHANNEL_U16:
    case MVR_CHANNEL_F32: return TypeDesc::FLOAT;
    case MVR_CHANNEL_U32: return TypeDesc::UINT;
    }
    return TypeDesc::FLOAT;
}

// One value of channel c at p, stored at to in exr_type(c->type).
static void put_native(const mvr_image_channel *c, const unsigned char *p, unsigned char *to)
{
    float f = 0.0f;
    switch (c->type) {
    case MVR_CHANNEL_U8: f = float(*p); break;
    case MVR_CHANNEL_U16: { uint16_t v; std::memcpy(&v, p, 2); f = float(v); break; }
    case MVR_CHANNEL_U32: std::memcpy(to, p, 4); return;
    case MVR_CHANNEL_F16:
    case MVR_CHANNEL_F32: std::memcpy(&f, p, 4); break;
    }
    if (exr_type(c->type) == TypeDesc::HALF) {
        half h(f);
        std::memcpy(to, &h, sizeof h);
    } else {
        std::memcpy(to, &f, 4);
    }
}

// The channels interleaved in their stored types (OpenImageIO's "native"
// layout for per-channel formats), rows top first, written in one call.
static mvr_result oiio_write_channels(const char *path, const mvr_image_channels *image, mvr_error *error)
{
    if (!path || !image || !image->channels || image->count == 0)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_write_channels: NULL or empty image");
    try {
        int n = int(image->count);
        ImageSpec spec(int(image->width), int(image->height), n, TypeDesc::FLOAT);
        spec.channelnames.clear();
        std::vector<size_t> offset(image->count);
        size_t pixel_bytes = 0;
        for (uint32_t k = 0; k < image->count; ++k) {
            TypeDesc t = exr_type(image->channels[k].type);
            spec.channelnames.emplace_back(image->channels[k].name);
            spec.channelformats.push_back(t);
            offset[k] = pixel_bytes;
            pixel_bytes += t.size();
        }
        // channels named nothing special: no alpha or depth roles guessed
        spec.alpha_channel = -1;
        spec.z_channel = -1;
        for (int k = 0; k < n; ++k) {
            if (spec.channelnames[size_t(k)] == "A")
                spec.alpha_channel = k;
            if (spec.channelnames[size_t(k)] == "Z")
                spec.z_channel = k;
        }
        size_t w = image->width, h = image->height;
        std::vector<unsigned char> native(w * h * pixel_bytes);
        for (size_t y = 0; y < h; ++y) {
            size_t row = image->bottom_up ? h - 1 - y : y;
            for (uint32_t k = 0; k < image->count; ++k) {
                const mvr_image_channel *c = &image->channels[k];
                const unsigned char *in = static_cast<const unsigned char *>(c->first) + row * c->row_stride;
                unsigned char *to = native.data() + y * w * pixel_bytes + offset[k];
                for (size_t x = 0; x < w; ++x, in += c->pixel_stride, to += pixel_bytes)
                    put_native(c, in, to);
            }
        }
        auto out = ImageOutput::create("exr");
        if (!out || !out->open(path, spec))
            return fail(error, MVR_ERROR_IO,
                        std::string("mvr_image_write_channels(") + path + "): " +
                            (out ? out->geterror() : OIIO::geterror()));
        bool ok = out->write_image(TypeDesc::UNKNOWN, native.data());
        std::string err = ok ? "" : out->geterror();
        if (!out->close() || !ok)
            return fail(error, MVR_ERROR_IO, std::string("mvr_image_write_channels(") + path + "): " + err +
                                                 out->geterror());
        return MVR_OK;
    } catch (const std::exception &e) {
        return fail(error, MVR_ERROR_IO, std::string("mvr_image_write_channels: ") + e.what());
    } catch (...) {
        return fail(error, MVR_ERROR_INTERNAL, "mvr_image_write_channels: unknown exception");
    }
}

static mvr_result oiio_compare(const mvr_image_view *a, const mvr_image_view *b, double threshold,
                                        const char *diff_path, mvr_image_compare_result *out, mvr_error *error)
{
    if (!a || !b || !out)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_compare: NULL argument");
    if (a->width != b->width || a->height != b->height)
        return fail(error, MVR_ERROR_INVALID_ARGUMENT,
                    "mvr_image_compare: sizes differ (" + std::to_string(a->width) + "x" + std::to_string(a->height) +
                        " vs " + std::to_string(b->width) + "x" + std::to_string(b->height) + ")");
    try {
        ImageBuf A, B;
        if (!to_buf(a, A, true) || !to_buf(b, B, true))
            return fail(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_compare: bad pixels");
        // a difference counts as over the threshold only when strictly greater
        // (OIIO 2.4 sets CompareResults::error when pixels fail the threshold:
        // a result, not a failure of the call; the inputs were checked above)
        ImageBufAlgo::CompareResults r = ImageBufAlgo::compare(A, B, float(threshold), float(threshold));
        out->rmse = r.rms_error;
        out->psnr = r.PSNR;
        out->max_abs = r.maxerror;
        out->mean_abs = r.meanerror;
        out->pixels_over = uint64_t(r.nfail);
        out->fraction_over = double(r.nfail) / (double(a->width) * double(a->height));
        if (diff_path) {
            ImageBuf diff = ImageBufAlgo::absdiff(A, B);
            ImageSpec spec = diff.spec();
            spec.set_format(TypeDesc::UINT8);
            // alpha 1 so the difference is visible in any viewer
            ImageBufAlgo::fill(diff, {1.0f}, ROI(0, diff.spec().width, 0, diff.spec().height, 0, 1, 3, 4));
            if (!diff.write(diff_path, TypeDesc::UINT8))
                return fail(error, MVR_ERROR_IO, std::string("mvr_image_compare: ") + diff.geterror());
        }
        return MVR_OK;
    } catch (const std::exception &e) {
        return fail(error, MVR_ERROR_INTERNAL, std::string("mvr_image_compare: ") + e.what());
    } catch (...) {
        return fail(error, MVR_ERROR_INTERNAL, "mvr_image_compare: unknown exception");
    }
}

// The module's one exported symbol (-fvisibility=hidden and a version script
// keep everything else, OpenImageIO's templates included, local).
static const mvr_image_backend oiio_backend = {
    MVR_IMAGE_MODULE_ABI, sizeof(mvr_image_backend), oiio_probe, oiio_decode_cost, oiio_decode, oiio_read, oiio_write,
    oiio_compare, oiio_write_channels,
};

extern "C" __attribute__((visibility("default"))) const mvr_image_backend *mvr_image_oiio_backend(uint32_t abi)
{
    return abi == MVR_IMAGE_MODULE_ABI ? &oiio_backend : nullptr;
}
