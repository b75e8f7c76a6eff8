// File access for glTF URIs: one resolver, confined to the asset's folder.
// glTF 2.0, 2.8 (URIs): relative references resolved against the glTF's
// location, or data: URIs (RFC 2397); reserved characters percent-encoded
// (RFC 3986, 2.1). Nothing else is read: no absolute paths, no other
// scheme, no current-directory search, no escape by ".." or symbolic links.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

#include "gltf_files.hpp"

namespace mvr_gltf {

std::string quote(const std::string &value)
{
    constexpr size_t max_chars = 80;
    std::string out = "'";
    size_t n = 0;
    for (unsigned char c : value) {
        if (n == max_chars) {
            out += "...";
            break;
        }
        if (c < 0x20 || c == 0x7F) {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += char(c);
        }
        ++n;
    }
    return out + "'";
}

static std::string mib(uint64_t bytes)
{
    char s[64];
    std::snprintf(s, sizeof s, "%.1f MiB", double(bytes) / 1048576.0);
    return s;
}

void budget::charge(uint64_t bytes, const std::string &what)
{
    if (bytes > limit || used > limit - bytes)
        throw load_error(MVR_ERROR_OUT_OF_MEMORY, what + " needs " + mib(bytes) + " more, over the load's memory budget (" +
                                                      mib(limit) + ", " + mib(used) +
                                                      " in use; mvr_gltf_options.memory_budget)");
    used += bytes;
    if (used > peak)
        peak = used;
}

static int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

bool percent_decode(const std::string &in, std::string *out, bool allow_nul)
{
    out->clear();
    out->reserve(in.size());
    for (size_t i = 0; i < in.size(); ++i) {
        char c = in[i];
        if (c == '%') {
            if (i + 2 >= in.size())
                return false;
            int hi = hex_value(in[i + 1]), lo = hex_value(in[i + 2]);
            if (hi < 0 || lo < 0)
                return false;
            c = char(hi * 16 + lo);
            i += 2;
        }
        if (c == '\0' && !allow_nul)
            return false;
        out->push_back(c);
    }
    return true;
}

// RFC 3986, 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) before
// the first ':' and before any '/', '?' or '#'. "C:/x" has the scheme "C".
static std::string scheme_of(const std::string &uri)
{
    size_t colon = uri.find(':');
    if (colon == std::string::npos || colon == 0)
        return "";
    for (size_t i = 0; i < colon; ++i) {
        unsigned char c = uri[i];
        bool ok = std::isalpha(c) || (i > 0 && (std::isdigit(c) || c == '+' || c == '-' || c == '.'));
        if (!ok)
            return "";
    }
    return uri.substr(0, colon);
}

static bool base64_value(unsigned char c, unsigned *v)
{
    if (c >= 'A' && c <= 'Z')
        *v = c - 'A';
    else if (c >= 'a' && c <= 'z')
        *v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
        *v = c - '0' + 52;
    else if (c == '+')
        *v = 62;
    else if (c == '/')
        *v = 63;
    else
        return false;
    return true;
}

file_resolver::file_resolver(const std::string &base_dir, bool allow_files, const mvr_gltf_file_access &access,
                             uint64_t max_file_bytes, budget &mem)
    : base_(base_dir), allow_files_(allow_files), access_(access), max_file_bytes_(max_file_bytes), mem_(mem)
{
}

read_result file_resolver::read(const std::string &uri, const std::string &what, bool shared)
{
    std::string scheme = scheme_of(uri);
    for (char &c : scheme)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    if (scheme == "data") {
        read_result r = read_data_uri(uri, what);
        r.fresh = true;
        return r;
    }
    if (uri.empty())
        refuse(what + " is empty");
    if (!scheme.empty())
        refuse(what + " " + quote(uri) + ": the scheme " + quote(scheme) +
               " is not read (only data: URIs and relative paths)");
    // a query or fragment is not part of the path (RFC 3986, 3.4 / 3.5)
    std::string path = uri.substr(0, uri.find_first_of("?#"));
    std::string decoded;
    if (!percent_decode(path, &decoded, false))
        refuse(what + " " + quote(uri) + ": malformed percent-encoding (or an encoded NUL)");
    read_result r;
    if (access_.read) {
        if (!decoded.empty() && (decoded[0] == '/' || decoded[0] == '\\'))
            refuse(what + " " + quote(uri) + ": absolute paths are refused (URIs are relative to the asset's folder)");
        r.key = "callback:" + decoded;
    } else {
        r.key = confine(decoded, uri, what);
    }
    auto found = cache_.find(r.key);
    r.fresh = found == cache_.end();
    if (!r.fresh)
        r.data = found->second;
    else if (access_.read)
        r.data = read_callback(decoded, uri, what);
    else
        r.data = read_file(r.key, uri, what);
    if (shared)
        cache_[r.key] = r.data;
    return r;
}

static bool under(const std::string &path, const std::string &root)
{
    if (root == "/")
        return true;
    return path.size() > root.size() && path.compare(0, root.size(), root) == 0 && path[root.size()] == '/';
}

static std::string real_path(const std::string &p)
{
    char *r = ::realpath(p.c_str(), nullptr);
    if (!r)
        return "";
    std::string s = r;
    std::free(r);
    return s;
}

// The real path of the file a decoded relative path names, once it is known
// to stay under an allowed root, lexically and after symbolic links.
std::string file_resolver::confine(const std::string &decoded, const std::string &uri, const std::string &what)
{
    std::string d = decoded;
    for (char &c : d)
        if (c == '\\')
            c = '/'; /* Windows exporters write backslashes; never a way around the checks */
    if (!d.empty() && d[0] == '/')
        refuse(what + " " + quote(uri) + ": absolute paths are refused (URIs are relative to the asset's folder)");
    if (!allow_files_)
        refuse(what + " " + quote(uri) +
               ": external files are refused (loaded from memory without a base_dir or a file_access.read)");
    if (!roots_ready_) {
        std::string base = real_path(base_.empty() ? "." : base_);
        if (base.empty())
            throw load_error(MVR_ERROR_IO, "the asset folder " + quote(base_) + " cannot be opened");
        roots_.push_back(base);
        if (access_.allowed_root) {
            std::string root = real_path(access_.allowed_root);
            if (root.empty())
                throw load_error(MVR_ERROR_IO, "file_access.allowed_root " + quote(access_.allowed_root) +
                                                   " cannot be opened");
            roots_.push_back(root);
        }
        roots_ready_ = true;
    }
    // lexical normalisation against the folder's real path: "." and empty
    // segments vanish, ".." removes the last segment
    std::vector<std::string> parts;
    {
        const std::string &base = roots_[0];
        size_t at = 1;
        while (at <= base.size()) {
            size_t end = base.find('/', at);
            if (end == std::string::npos)
                end = base.size();
            if (end > at)
                parts.push_back(base.substr(at, end - at));
            at = end + 1;
        }
    }
    size_t at = 0;
    while (at <= d.size()) {
        size_t end = d.find('/', at);
        if (end == std::string::npos)
            end = d.size();
        std::string seg = d.substr(at, end - at);
        if (seg == "..") {
            if (!parts.empty())
                parts.pop_back();
        } else if (!seg.empty() && seg != ".") {
            parts.push_back(seg);
        }
        at = end + 1;
    }
    std::string lexical;
    for (const auto &p : parts)
        lexical += "/" + p;
    if (lexical.empty())
        lexical = "/";
    bool inside = false;
    for (const auto &root : roots_)
        inside = inside || under(lexical, root);
    if (!inside)
        refuse(what + " " + quote(uri) + ": the path leaves the asset's folder");
    // Symbolic links: the real path must stay inside too. One answer for a
    // link that leads out and for one that leads nowhere, so a refusal never
    // tells whether a path outside the folder exists.
    const std::string link_out = ": it goes through a symbolic link that does not resolve inside the asset's folder";
    std::string real = real_path(lexical);
    if (real.empty()) {
        // missing: plainly (no link on the way), or behind a link
        std::string prefix;
        for (const auto &p : parts) {
            prefix += "/" + p;
            struct stat sb;
            if (::lstat(prefix.c_str(), &sb) != 0)
                break;
            if (S_ISLNK(sb.st_mode))
                refuse(what + " " + quote(uri) + link_out);
        }
        throw load_error(MVR_ERROR_IO, what + " " + quote(uri) + ": no such file in the asset's folder");
    }
    inside = false;
    for (const auto &root : roots_)
        inside = inside || under(real, root);
    if (!inside)
        refuse(what + " " + quote(uri) + link_out);
    return real;
}

shared_bytes file_resolver::read_file(const std::string &path, const std::string &uri, const std::string &what)
{
    // O_NONBLOCK: opening a FIFO must not wait for a writer
    int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0)
        throw load_error(MVR_ERROR_IO, what + " " + quote(uri) + ": cannot be opened (" + std::strerror(errno) + ")");
    struct stat sb;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        ::close(fd);
        refuse(what + " " + quote(uri) + ": not a regular file");
    }
    uint64_t size = uint64_t(sb.st_size);
    if (size > max_file_bytes_) {
        ::close(fd);
        refuse(what + " " + quote(uri) + ": " + std::to_string(size) + " bytes, over the cap of " +
               std::to_string(max_file_bytes_) + " (mvr_gltf_options.max_file_bytes)");
    }
    auto out = std::make_shared<owned_bytes>();
    try {
        mem_.charge(size, what + " " + quote(uri));
    } catch (...) {
        ::close(fd);
        throw;
    }
    out->mem = &mem_;
    try {
        out->bytes.resize(size_t(size));
    } catch (...) {
        ::close(fd);
        out->mem = nullptr;
        mem_.release(size);
        throw;
    }
    size_t got = 0;
    while (got < size) {
        ssize_t n = ::read(fd, out->bytes.data() + got, size_t(size) - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += size_t(n);
    }
    ::close(fd);
    if (got != size)
        throw load_error(MVR_ERROR_IO, what + " " + quote(uri) + ": read " + std::to_string(got) + " of " +
                                           std::to_string(size) + " bytes");
    return out;
}

shared_bytes file_resolver::read_callback(const std::string &decoded, const std::string &uri, const std::string &what)
{
    void *data = nullptr;
    size_t size = 0;
    mvr_result r = access_.read(decoded.c_str(), max_file_bytes_, &data, &size, access_.user_data);
    auto release = [&] {
        if (!data)
            return;
        if (access_.release)
            access_.release(data, access_.user_data);
        else
            std::free(data);
    };
    if (r != MVR_OK) {
        release();
        throw load_error(r == MVR_ERROR_OUT_OF_MEMORY ? r : MVR_ERROR_IO,
                         what + " " + quote(uri) + ": file_access.read failed (" + mvr_result_name(r) + ")");
    }
    if (size > 0 && !data) {
        throw load_error(MVR_ERROR_IO, what + " " + quote(uri) + ": file_access.read returned no data");
    }
    if (size > max_file_bytes_) {
        release();
        refuse(what + " " + quote(uri) + ": file_access.read returned " + std::to_string(size) +
               " bytes, over the cap of " + std::to_string(max_file_bytes_) + " (mvr_gltf_options.max_file_bytes)");
    }
    auto out = std::make_shared<owned_bytes>();
    try {
        mem_.charge(size, what + " " + quote(uri));
        out->mem = &mem_;
        out->bytes.assign(static_cast<unsigned char *>(data), static_cast<unsigned char *>(data) + size);
    } catch (...) {
        release();
        throw;
    }
    release();
    return out;
}

// RFC 2397: data:[<mediatype>][;base64],<data>; without ";base64" the data
// is percent-encoded text.
read_result file_resolver::read_data_uri(const std::string &uri, const std::string &what)
{
    size_t comma = uri.find(',');
    if (comma == std::string::npos)
        refuse(what + " " + quote(uri) + ": a data: URI without ','");
    std::string header = uri.substr(5, comma - 5);
    bool base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
    read_result r;
    r.media_type = base64 ? header.substr(0, header.size() - 7) : header;
    r.media_type = r.media_type.substr(0, r.media_type.find(';'));
    const size_t n = uri.size() - comma - 1;
    const char *p = uri.data() + comma + 1;
    charged held(mem_, uint64_t(n), what);   // the decoded bytes are at most as many as the encoded ones
    std::vector<unsigned char> bytes;
    if (base64) {
        bytes.reserve(n / 4 * 3 + 3);
        unsigned acc = 0, bits = 0;
        size_t i = 0;
        for (; i < n && p[i] != '='; ++i) {
            unsigned v;
            if (!base64_value(static_cast<unsigned char>(p[i]), &v))
                refuse(what + ": the data: URI's base64 has a bad character at offset " + std::to_string(i));
            acc = (acc << 6) | v;
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                bytes.push_back(static_cast<unsigned char>(acc >> bits));
                acc &= (1u << bits) - 1;
            }
        }
        for (; i < n; ++i)
            if (p[i] != '=')
                refuse(what + ": the data: URI's base64 continues after its padding");
    } else {
        std::string decoded;
        if (!percent_decode(std::string(p, n), &decoded, true))
            refuse(what + ": the data: URI has malformed percent-encoding");
        bytes.assign(decoded.begin(), decoded.end());
    }
    // hand the charge over to the bytes' owner, for what it holds
    auto out = std::make_shared<owned_bytes>();
    out->bytes = std::move(bytes);
    out->mem = &mem_;
    held.bytes = uint64_t(n) - out->bytes.size();
    r.data = out;
    return r;
}

}  // namespace mvr_gltf
