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
    if ((bytes > limit || used > limit - bytes) && drop_spare)
        drop_spare();
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

static std::string real_path(const std::string &p)
{
    char *r = ::realpath(p.c_str(), nullptr);
    if (!r)
        return "";
    std::string s = r;
    std::free(r);
    return s;
}

// The components of a path, "" and "." left out ("a//./b" is "a/b" to the
// kernel too); ".." is kept: only the walk knows what it climbs out of.
static std::vector<std::string> components(const std::string &path)
{
    std::vector<std::string> out;
    size_t at = 0;
    while (at <= path.size()) {
        size_t end = path.find('/', at);
        if (end == std::string::npos)
            end = path.size();
        if (end > at && path.compare(at, end - at, ".") != 0)
            out.push_back(path.substr(at, end - at));
        at = end + 1;
    }
    return out;
}

namespace {

struct unique_fd {
    int fd = -1;
    explicit unique_fd(int f) : fd(f) {}
    unique_fd(unique_fd &&o) noexcept : fd(o.fd) { o.fd = -1; }
    unique_fd &operator=(unique_fd &&) = delete;
    unique_fd(const unique_fd &) = delete;
    ~unique_fd()
    {
        if (fd >= 0)
            ::close(fd);
    }
};

// Where a walk stands: a root and the folders below it, each opened from the
// one above it without following a link, so the innermost descriptor is
// inside the root whatever is renamed or relinked meanwhile.
struct cursor {
    const file_resolver::root_dir *root = nullptr;
    std::vector<unique_fd> dirs;
    int fd() const { return dirs.empty() ? root->fd : dirs.back().fd; }
};

// The longest root whose components begin `parts`; how many it covers.
const file_resolver::root_dir *root_of(const std::vector<file_resolver::root_dir> &roots,
                                       const std::vector<std::string> &parts, size_t *covered)
{
    const file_resolver::root_dir *best = nullptr;
    for (const auto &r : roots) {
        std::vector<std::string> rp = components(r.path);
        if (rp.size() > parts.size() || (best && rp.size() <= *covered))
            continue;
        bool prefix = true;
        for (size_t i = 0; i < rp.size() && prefix; ++i)
            prefix = rp[i] == parts[i];
        if (prefix) {
            best = &r;
            *covered = rp.size();
        }
    }
    return best;
}

// A symbolic link's text: 1, not a link: 0 (errno from readlinkat), a text
// too long to resolve: 1 with an empty text.
int read_link(int dir, const std::string &name, std::string *text)
{
    std::vector<char> buf(PATH_MAX);
    ssize_t n = ::readlinkat(dir, name.c_str(), buf.data(), buf.size());
    if (n < 0)
        return 0;
    text->assign(buf.data(), size_t(n) < buf.size() ? size_t(n) : 0);
    return 1;
}

}  // namespace

void file_resolver::open_roots()
{
    if (roots_ready_)
        return;
    auto add = [&](const std::string &given, const std::string &name) {
        root_dir r;
        r.path = real_path(given);
        if (!r.path.empty())
            r.fd = ::open(r.path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (r.fd < 0)
            throw load_error(MVR_ERROR_IO, name + " " + quote(given) + " cannot be opened");
        roots_.push_back(r);
    };
    add(base_.empty() ? "." : base_, "the asset folder");
    if (access_.allowed_root)
        add(access_.allowed_root, "file_access.allowed_root");
    roots_ready_ = true;
}

file_resolver::~file_resolver()
{
    for (const auto &r : roots_)
        ::close(r.fd);
}

// Opens the file a decoded relative path names without a window between
// check and use: the URI's dot-segments are removed as text (RFC 3986,
// 5.2.4) and the result must lie under a root; then every component is opened
// with openat(O_NOFOLLOW) from the descriptor of the folder above it. A
// symbolic link met on the way is resolved here, as POSIX resolves pathnames
// (XBD 4.13: its text replaces it, relative to the folder holding it), and
// is kept only while the walk stays under a root: links inside the folder
// keep working, and nothing outside a root is ever opened. A link that leads
// out and one that leads nowhere get one answer, so a refusal never tells
// whether a path outside the folder exists.
int file_resolver::open_confined(const std::string &decoded, const std::string &uri, const std::string &what)
{
    std::string d = decoded;
    for (char &c : d)
        if (c == '\\')
            c = '/'; /* Windows exporters write backslashes; never a way around the checks */
    const std::string named = what + " " + quote(uri);
    if (!d.empty() && d[0] == '/')
        refuse(named + ": absolute paths are refused (URIs are relative to the asset's folder)");
    if (!allow_files_)
        refuse(named + ": external files are refused (loaded from memory without a base_dir or a file_access.read)");
    open_roots();
    std::vector<std::string> parts = components(roots_[0].path);
    for (const std::string &seg : components(d)) {
        if (seg != "..")
            parts.push_back(seg);
        else if (!parts.empty())
            parts.pop_back();
    }
    size_t covered = 0;
    cursor c;
    c.root = root_of(roots_, parts, &covered);
    if (!c.root || covered == parts.size())
        refuse(named + ": the path leaves the asset's folder");
    // what is left to walk, next component last
    std::vector<std::string> pending(parts.rbegin(), parts.rend() - long(covered));
    const std::string link_out = ": it goes through a symbolic link that does not resolve inside the asset's folder";
    constexpr int max_links = 40;   // Linux's MAXSYMLINKS
    int links = 0;
    while (!pending.empty()) {
        std::string name = std::move(pending.back());
        pending.pop_back();
        if (name == "..") {
            // only from a link's text (the URI's went above); climbing out of
            // a root re-enters a root above it, or leaves
            if (!c.dirs.empty()) {
                c.dirs.pop_back();
                continue;
            }
            std::vector<std::string> up = components(c.root->path);
            if (up.empty())
                continue;   // "/.." is "/"
            up.pop_back();
            const root_dir *r = root_of(roots_, up, &covered);
            if (!r)
                refuse(named + link_out);
            c.dirs.clear();
            c.root = r;
            for (size_t i = up.size(); i > covered; --i)
                pending.push_back(up[i - 1]);
            continue;
        }
        bool last = pending.empty();
        int flags = O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NOCTTY | (last ? O_NONBLOCK : O_DIRECTORY);
        int fd = ::openat(c.fd(), name.c_str(), flags);
        if (fd >= 0) {
            if (last)
                return fd;
            c.dirs.emplace_back(fd);
            continue;
        }
        int err = errno;
        std::string text;
        if (!read_link(c.fd(), name, &text)) {
            // ELOOP from a link that was swapped back for a file meanwhile: again
            if (err == ELOOP && ++links <= max_links) {
                pending.push_back(name);
                continue;
            }
            if (err == ENOENT || err == ENOTDIR)
                throw load_error(MVR_ERROR_IO, named + ": no such file in the asset's folder");
            throw load_error(MVR_ERROR_IO, named + ": cannot be opened (" + std::strerror(err) + ")");
        }
        if (++links > max_links)
            throw load_error(MVR_ERROR_IO, named + ": more than 40 symbolic links on the way");
        if (text.empty())
            refuse(named + link_out);
        std::vector<std::string> target = components(text);
        if (text[0] == '/') {
            // absolute: it must name a root first (roots are real paths, so
            // their components are compared as text)
            const root_dir *r = root_of(roots_, target, &covered);
            if (!r)
                refuse(named + link_out);
            c.dirs.clear();
            c.root = r;
            target.erase(target.begin(), target.begin() + long(covered));
        }
        pending.insert(pending.end(), target.rbegin(), target.rend());
        if (pending.empty())
            refuse(named + ": not a regular file");   // a link to a root itself
    }
    refuse(named + ": not a regular file");
}

shared_bytes file_resolver::read_fd(int fd, uint64_t size, const std::string &uri, const std::string &what)
{
    if (size > max_file_bytes_)
        refuse(what + " " + quote(uri) + ": " + std::to_string(size) + " bytes, over the cap of " +
               std::to_string(max_file_bytes_) + " (mvr_gltf_options.max_file_bytes)");
    auto out = std::make_shared<owned_bytes>();
    mem_.charge(size, what + " " + quote(uri));
    out->mem = &mem_;
    try {
        out->bytes.resize(size_t(size));
    } catch (...) {
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
    if (got != size)
        throw load_error(MVR_ERROR_IO, what + " " + quote(uri) + ": read " + std::to_string(got) + " of " +
                                           std::to_string(size) + " bytes");
    return out;
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
        auto found = cache_.find(r.key);
        r.fresh = found == cache_.end();
        r.data = r.fresh ? read_callback(decoded, uri, what) : found->second;
    } else {
        // everything below comes from the one descriptor the walk opened:
        // what was checked is what is read
        unique_fd file(open_confined(decoded, uri, what));
        struct stat sb;
        if (fstat(file.fd, &sb) != 0 || !S_ISREG(sb.st_mode))
            refuse(what + " " + quote(uri) + ": not a regular file");
        // the same file however it is spelled or linked
        r.key = "file:" + std::to_string(uint64_t(sb.st_dev)) + ":" + std::to_string(uint64_t(sb.st_ino));
        auto found = cache_.find(r.key);
        r.fresh = found == cache_.end();
        r.data = r.fresh ? read_fd(file.fd, uint64_t(sb.st_size), uri, what) : found->second;
    }
    if (shared)
        cache_[r.key] = r.data;
    return r;
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
