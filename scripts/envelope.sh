#!/usr/bin/env bash
# The numerics envelope (docs/numerics.md, "Envelope"): sweeps of distance,
# scale and squash, each scene rendered as `vkray render SCENE --size
# 160x120 --check --precision MODE` does, one line per render: the share of
# pixels that differ (colour above 0.02, id, depth or normal), the share the
# margin rule sets aside, and render --check's verdict (PASS: no pixel
# unexplained; docs/gpu-vs-reference.md, "The margin rule"). The swept
# scenes are written to DIR (default: a temporary folder, removed after); the
# fixed ones are tests/data/envelope/.
#
#   scripts/envelope.sh [--vkray BINARY] [--keep DIR] [SWEEP...]
#   sweeps: near (huge shapes seen from close), far (a unit sphere seen from
#   afar, plain and checkered), squash (outermost and innermost), files
#   (tests/data/envelope/*.sdl); default all.
set -euo pipefail
cd "$(dirname "$0")/.."
vkray=build/vkray
keep=""
sweeps=()
while [ $# -gt 0 ]; do
    case "$1" in
    --vkray) vkray="$2"; shift 2 ;;
    --keep) keep="$2"; shift 2 ;;
    *) sweeps+=("$1"); shift ;;
    esac
done
[ ${#sweeps[@]} -gt 0 ] || sweeps=(near far squash files)
if [ -n "$keep" ]; then
    dir="$keep"
    mkdir -p "$dir"
else
    dir="$(mktemp -d)"
    trap 'rm -rf "$dir"' EXIT
fi

# check SCENE MODE LABEL: one line of figures.
check() {
    local out differ aside verdict
    out="$("$vkray" render "$1" --size 160x120 --check --precision "$2" -o "$dir/out.png" 2>&1 || true)"
    differ="$(sed -n 's/^differing .*(\([^ ]*\) %):.*/\1/p' <<<"$out")"
    aside="$(sed -n 's/^set aside .*(\([^ ]*\) %):.*/\1/p' <<<"$out")"
    verdict="$(sed -n 's/^result *//p' <<<"$out")"
    if [ -z "$verdict" ]; then
        verdict="error: $(grep -m1 'error' <<<"$out" | cut -c1-100)"
    fi
    printf '%-44s %-7s differ %8s %%  set aside %8s %%  %s\n' "$3" "$2" "${differ:--}" "${aside:--}" "$verdict"
}

# A shape of size R seen from H above its surface at the point (0, R, 0) of
# world space, lit from above (R, H, SHAPE: sphere, cylinder, torus).
near() {
    local r="$1" h="$2" shape="$3" file="$dir/near_${3}_${1}_${2}.sdl"
    awk -v R="$r" -v H="$h" -v S="$shape" 'BEGIN {
        printf "camera eye 0 %.17g 0 look %.17g %.17g %.17g up 0 1 0 fov 60\n", R + H, 30 * H, R, 20 * H
        print "background 0.1 0.1 0.3"
        printf "light %.17g %.17g %.17g 1 1 1\n", 500 * H, R + 1000 * H, 800 * H
        print "diffuse 0.3 0.5 0.8"
        if (S == "sphere") printf "push scale %s %s %s sphere pop\n", R, R, R
        # the wall x^2 + y^2 = R^2 of a long cylinder along z
        if (S == "cylinder") printf "push translate 0 0 %.17g scale %s %s %.17g cylinder pop\n", -5 * R, R, R, 10 * R
        # the outer equator of a torus of tube radius R: its centre circle has radius 4 R
        if (S == "torus") printf "push translate 0 %.17g 0 rotate 90 0 1 0 scale %.17g %.17g %.17g torus pop\n", -4 * R, 4 * R, 4 * R, 4 * R
    }' >"$file"
    echo "$file"
}

# A unit sphere seen from D radii, filling the view; checkered with cells S
# (0: plain).
far() {
    local d="$1" s="$2" file="$dir/far_${1}_${2}.sdl"
    awk -v D="$d" -v S="$s" 'BEGIN {
        n = sqrt(4000 ^ 2 + 3000 ^ 2 + 6244.998 ^ 2)
        x = D * 4000 / n; y = D * 3000 / n; z = D * 6244.998 / n
        printf "camera eye %.17g %.17g %.17g look 0 0 0 up 0 1 0 fov %.17g\n", x, y, z, 2 * atan2(1.4, D) * 45 / atan2(1, 1)
        printf "background 0.1 0.1 0.3\nlight %.17g %.17g %.17g 1 1 1\n", x, y + 3 * D, z
        print "globalAmbient 0.3 0.3 0.3 ambient 0.3 0.3 0.3 diffuse 0.7 0.7 0.7"
        if (S > 0) printf "texture 1 parameters 4 %s 0.8 0.2 0.2\n", S
        print "sphere"
    }' >"$file"
    echo "$file"
}

# A rotated SHAPE squashed by RATIO along z, by the outermost transform
# (WHERE = outer: scale ... rotate ... SHAPE) or the innermost (inner).
squash() {
    local shape="$1" ratio="$2" where="$3" file="$dir/squash_${3}_${2}_${1}.sdl"
    {
        echo "camera eye 2.2 -3.1 4.3 look 0 0 0 up 0 0 1 fov 40"
        echo "background 0.1 0.1 0.3"
        echo "light 4 -3 6 1 1 1"
        echo "light -3 4 -2 0.5 0.5 0.5"
        echo "globalAmbient 0.2 0.2 0.2 ambient 0.2 0.2 0.2 diffuse 0.8 0.5 0.3"
        if [ "$where" = outer ]; then
            echo "push scale 1.4 1.7 $ratio rotate 37 1 2 3 $shape pop"
        else
            echo "push rotate 37 1 2 3 scale 1.4 1.7 $ratio $shape pop"
        fi
    } >"$file"
    echo "$file"
}

for sweep in "${sweeps[@]}"; do
    case "$sweep" in
    near)
        echo "# near: a shape of size R seen from H above (R/H), robust and fp64"
        for rh in "2000 0.1" "1e5 0.01" "1e6 0.1" "1e7 1" "2e6 0.1" "2000 1e-4"; do
            set -- $rh
            for mode in robust fp64; do check "$(near "$1" "$2" sphere)" "$mode" "sphere R $1 H $2"; done
        done
        for mode in robust fp64; do
            check "$(near 3000 0.07 cylinder)" "$mode" "cylinder R 3000 H 0.07"
            check "$(near 500 0.05 torus)" "$mode" "torus tube 500 H 0.05"
        done
        ;;
    far)
        echo "# far: a unit sphere seen from D radii, plain (cells 0) or checkered with cells S"
        for d in 16000 32000 64000 128000; do check "$(far "$d" 0)" robust "sphere D $d plain"; done
        for s in 0.05 0.1 0.2 0.5; do
            for ratio in 10000 20000 40000 80000; do
                d="$(awk -v r="$ratio" -v s="$s" 'BEGIN { print r * s }')"
                check "$(far "$d" "$s")" robust "sphere D $d cells $s (D/S $ratio)"
            done
        done
        for d in 8000 32000 1000000 2000000; do
            check "$(far "$d" 0.05)" fp64 "sphere D $d cells 0.05"
            check "$(far "$d" 0)" fp64 "sphere D $d plain"
        done
        ;;
    squash)
        echo "# squash: a rotated shape squashed by RATIO, outermost (after the rotation) or innermost"
        for shape in cube sphere icosahedron teapot; do
            for ratio in 1e-5 5e-5 1e-4 1e-3; do check "$(squash "$shape" "$ratio" outer)" robust "$shape outer $ratio"; done
            check "$(squash "$shape" 1e-8 inner)" robust "$shape inner 1e-8"
            check "$(squash "$shape" 1e-5 outer)" fp64 "$shape outer 1e-5"
        done
        for shape in cube sphere icosahedron teapot; do
            for ratio in 1e-8 1e-10 1e-12; do check "$(squash "$shape" "$ratio" outer)" fp64 "$shape outer $ratio"; done
        done
        ;;
    files)
        echo "# files: tests/data/envelope"
        for file in tests/data/envelope/*.sdl; do
            for mode in robust fp64; do check "$file" "$mode" "$(basename "$file")"; done
        done
        ;;
    *) echo "envelope.sh: unknown sweep '$sweep' (near, far, squash, files)" >&2; exit 1 ;;
    esac
done
