#!/usr/bin/env bash
# Re-renders the hardware snapshot (reference/hardware/h200) on the GPU at hand and measures
# it, in one run: what a session with a hardware GPU does first (README.md beside this file).
#
#   reference/hardware/refresh.sh OCEAN OUT [--quick]
#
# OCEAN: a release `ocean` binary built from this checkout (no build happens here: carry one);
# OUT: a folder for the results, which end up as at most eight files:
#   snapshot.tgz.00, .01 …
#                  the 19 scenes re-rendered with `--backend gpu --dump-passes` (256×144),
#                  each at its manifest's time and scene, cut to the files the snapshot keeps
#                  (hdr.exr, ldr.png, the object maps, the wave maps and foam field of the three
#                  scenes that keep them) and the bloom chains, the spray's step and the
#                  displacement map it read, with the manifest's resources cut to match;
#   render.log     what each render printed;
#   selftest.json, selftest.log   `ocean selftest` (the envelope on every reference scene and
#                  planted bug; `--quick` with --quick);
#   bench.json, bench.log         `ocean bench --backend gpu` (`--quick` with --quick), with
#                  the water and objects shaded in compute and in the fragment stage:
#                  {"compute": …, "fragment": …}.
# Run from the repository's root (the reference scenes are read from there). Each step goes
# on when another fails, and says so; the exit status is the number of steps that failed.
#
# Back here: `cat snapshot.tgz.* | tar -xz -C DIR`, put DIR over reference/hardware/h200 (or
# beside it, for another GPU), then write the digests that
#   OCEAN_HARDWARE_DIGESTS=1 cargo test --release --test hardware_snapshot -- --nocapture
# prints into its oracle.json, with the commit and the adapter in its README.
set -u
if [ $# -lt 2 ]; then
    sed -n '2,27p' "$0" >&2
    exit 2
fi
ocean=$(realpath "$1")
out=$(realpath -m "$2")
quick=${3:-}
snapshot=reference/hardware/h200
if [ ! -x "$ocean" ] || [ ! -d "$snapshot" ]; then
    echo "refresh.sh: $ocean is not executable, or $snapshot is not here (run from the repository's root)" >&2
    exit 2
fi
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0

# 1. The snapshot's scenes, each as its manifest says.
: >"$out/render.log"
for dir in "$snapshot"/*/; do
    name=$(basename "$dir")
    # scene path or built-in system, time, width, height
    read -r scene system time width height < <(python3 - "$dir/manifest.json" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
f = m["frame"]
path = m["scene"]["path"]
print(path if path.endswith(".toml") else "-", f["system"], f["time_s"], f["width"], f["height"])
EOF
    )
    if [ "$scene" = "-" ]; then
        what=(--system "$system")
    else
        what=("$scene")
    fi
    echo "== $name: ocean render ${what[*]} --time $time --size ${width}x$height" >>"$out/render.log"
    if ! "$ocean" render "${what[@]}" --backend gpu --time "$time" --size "${width}x$height" \
        --dump-passes "$work/$name" -o "$work/$name.png" >>"$out/render.log" 2>&1; then
        echo "$name: the render failed (render.log)" | tee -a "$out/render.log"
        failed=$((failed + 1))
        continue
    fi
    # Keep what the snapshot keeps of this scene, and the spray's step where there is one.
    python3 - "$work/$name" "$dir" <<'EOF'
import json, os, sys
new, old = sys.argv[1], sys.argv[2]
keep = {f for f in os.listdir(old) if f != "manifest.json"}
keep |= {"spray_step.exr", "bloom_down.exr", "bloom_up.exr"}
# The spray's step is judged from the frame's displacement map: keep it with the step.
if os.path.exists(os.path.join(new, "spray_step.exr")):
    keep.add("displacement.exr")
m = json.load(open(os.path.join(new, "manifest.json")))
m["resources"] = [r for r in m["resources"] if r["file"] in keep]
for f in os.listdir(new):
    if f not in keep and f != "manifest.json":
        os.remove(os.path.join(new, f))
with open(os.path.join(new, "manifest.json"), "w") as o:
    json.dump(m, o, indent=2)
EOF
    rm -f "$work/$name.png"
done
# A file that comes back from a device machine holds at most 16 MiB: in parts of 15 MB.
tar -C "$work" -czf "$out/snapshot.tgz" . &&
    split -b 15000000 -d "$out/snapshot.tgz" "$out/snapshot.tgz." &&
    rm "$out/snapshot.tgz" &&
    echo "snapshot.tgz.*: $(ls "$work" | wc -l) scenes in $(ls "$out"/snapshot.tgz.* | wc -l) part(s)"

# 2. The verdict on every reference scene and planted bug.
"$ocean" selftest $quick --json "$out/selftest.json" >"$out/selftest.log" 2>&1 ||
    { echo "selftest failed (selftest.log)"; failed=$((failed + 1)); }
tail -n 1 "$out/selftest.log"

# 3. What a real-time user sees.
# Both shading paths (the same bits; which is faster on this GPU decides the default), in one
# JSON file: {"compute": …, "fragment": …}.
: >"$out/bench.log"
for path in compute fragment; do
    "$ocean" bench --backend gpu $quick --shading "$path" -o "$out/bench-$path.json" \
        >>"$out/bench.log" 2>&1 ||
        { echo "bench ($path) failed (bench.log)"; failed=$((failed + 1)); }
done
{
    printf '{"compute": '
    cat "$out/bench-compute.json" 2>/dev/null || printf 'null'
    printf ', "fragment": '
    cat "$out/bench-fragment.json" 2>/dev/null || printf 'null'
    printf '}\n'
} >"$out/bench.json"
rm -f "$out/bench-compute.json" "$out/bench-fragment.json"
echo "bench: $(wc -c <"$out/bench.json") bytes of JSON"
exit "$failed"
