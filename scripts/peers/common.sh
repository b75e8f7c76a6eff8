# scripts/peers/common.sh: sourced by bench_peers.sh and render_khronos.sh (which define log and
# die first). The pinned npm packages, the folder they go to (never the repository), the browser
# and the tools that drive it.

THREE_VERSION=0.187.0        # npm three (r187)
KHRONOS_VERSION=1.1.0        # npm @khronosgroup/gltf-viewer
PLAYWRIGHT_VERSION=1.65.1    # playwright-core (drives Debian's chromium; downloads no browser)

cache=${MVR_PEERS_DIR:-$HOME/.cache/mvr-peers}

# chromium_bin: $CHROMIUM, else Debian's real binary (its /usr/bin/chromium is a shell wrapper);
# node and npm must be there too.
peers_find_tools() {
    chromium_bin=${CHROMIUM:-}
    if [ -z "$chromium_bin" ]; then
        if [ -x /usr/lib/chromium/chromium ]; then chromium_bin=/usr/lib/chromium/chromium
        else chromium_bin=$(command -v chromium || true); fi
    fi
    [ -n "$chromium_bin" ] && [ -x "$chromium_bin" ] || die "no chromium: run scripts/setup --peers"
    command -v node >/dev/null 2>&1 || die "no node: run scripts/setup --peers"
    command -v npm >/dev/null 2>&1 || die "no npm: run scripts/setup --peers"
}

# peers_npm_install PACKAGE VERSION: it and playwright-core into $cache, unless both are there at
# their pinned versions.
peers_npm_install() {
    local package=$1 version=$2
    installed() { node -p "require('$cache/node_modules/$1/package.json').version" 2>/dev/null || true; }
    if [ "$(installed "$package")" != "$version" ] || [ "$(installed playwright-core)" != "$PLAYWRIGHT_VERSION" ]; then
        log "installing $package@$version and playwright-core@$PLAYWRIGHT_VERSION into $cache"
        mkdir -p "$cache"
        [ -f "$cache/package.json" ] || printf '{ "name": "mvr-peers", "private": true }\n' > "$cache/package.json"
        (cd "$cache" && npm install --no-audit --no-fund --loglevel=error \
            "$package@$version" "playwright-core@$PLAYWRIGHT_VERSION")
    fi
}
