#!/usr/bin/env bash
# Draws the wall images in tests/data with ImageMagick, a tool that is not Mason, so that the
# PNG reader is tested on drawings it did not make. Installs ImageMagick from Debian's
# packages if it is missing. The PNGs are committed; the tests only read them, so this script
# is run only to change them.
#
#   scripts/draw-fixtures.sh            # writes tests/data/*-imagemagick.png
set -euo pipefail
cd "$(dirname "$0")/.."

# A real ImageMagick `convert` (some machines put a stand-in first on PATH).
find_convert() {
    for c in magick /usr/bin/convert convert; do
        if command -v "$c" >/dev/null 2>&1 && "$c" -version 2>/dev/null | grep -q ImageMagick; then
            echo "$c"
            return 0
        fi
    done
    return 1
}
if ! CONVERT=$(find_convert); then
    SUDO=""
    if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends imagemagick >/dev/null
    CONVERT=$(find_convert)
fi

# draw OUT UNIT_PX LAYER_PX STROKE_PX STROKE BACKGROUND MARGIN "LAYER TEXT (top first, / between layers)"
# Each brick is a rectangle filled with its colour and outlined by a stroke centred on its
# edge, as a person draws one in a vector tool; ImageMagick anti-aliases the edges.
draw() {
    local out=$1 unit=$2 layer=$3 stroke=$4 stroke_colour=$5 background=$6 margin=$7 text=$8
    local -a rows
    IFS='/' read -r -a rows <<<"$text"
    local levels=${#rows[@]} width=0 args=() y=$margin
    for row in "${rows[@]}"; do
        local x=0
        for token in $row; do
            local units fill
            case $token in
                R) units=1; fill='#e8201c' ;;
                G) units=2; fill='#1ec83a' ;;
                B) units=4; fill='#1e3cf0' ;;
                O) units=6; fill='#ffa500' ;;
                .) units=1; fill='' ;;
                *) echo "unknown token $token" >&2; exit 2 ;;
            esac
            if [ -n "$fill" ]; then
                local x0=$((margin + x * unit)) x1=$((margin + (x + units) * unit))
                args+=(-fill "$fill" -draw "rectangle $x0,$y $x1,$((y + layer))")
            fi
            x=$((x + units))
        done
        if [ $x -gt $width ]; then width=$x; fi
        y=$((y + layer))
    done
    local stroke_args=(-stroke none)
    if [ "$stroke" != 0 ]; then stroke_args=(-stroke "$stroke_colour" -strokewidth "$stroke"); fi
    "$CONVERT" -size "$((width * unit + 2 * margin + 1))x$((levels * layer + 2 * margin + 1))" \
        "xc:$background" "${stroke_args[@]}" "${args[@]}" "$out"
    echo "drew $out"
}

# Three layers in black outlines, layers 1.4 units tall.
draw tests/data/wall-imagemagick.png 28 40 2 black white 6 "R G R/G B R G/B O R G"
# The thesis's Figure 3.2 wall (2 levels of 5 bricks, our built-in thesis-2x5 colours; the
# thesis does not publish its figure's colours), square bricks in grey outlines on grey paper.
draw tests/data/thesis-figure-3-2-imagemagick.png 50 50 3 '#707070' '#e6e6e6' 10 "R G B G R/G B R R G"
# No outlines at all, thin layers (0.75 units), cream paper; touching reds are read as two.
draw tests/data/wall-imagemagick-borderless.png 24 18 0 none '#f5efdc' 8 "R R G . B/O R R G R R"
# The proportions the first reader could not read (layers 1.25, 1.0, 0.4 and 2.0 units tall),
# then changed as an image tool changes a drawing: scaled by a fraction, scaled with Lanczos
# (its ringing overshoots the edges), stretched unevenly, blurred.
W3="R G R/G B R G/B O R G"
W5="G R G R . B/O R G R R/B B G R/R O R G R/G G B R R R"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
draw "$tmp/125.png" 20 25 2 black white 5 "$W3"
"$CONVERT" "$tmp/125.png" -resize 61.8% tests/data/wall-imagemagick-125-scaled.png
draw "$tmp/100.png" 20 20 1 '#808080' white 5 "$W3"
"$CONVERT" "$tmp/100.png" -resize 173% tests/data/wall-imagemagick-100-scaled.png
draw "$tmp/040.png" 30 12 2 white '#f5efdc' 5 "$W3"
"$CONVERT" "$tmp/040.png" -resize 80%x130% tests/data/wall-imagemagick-040-stretched.png
draw "$tmp/200.png" 16 32 0 none white 5 "$W3"
"$CONVERT" "$tmp/200.png" -filter Lanczos -resize 150% tests/data/wall-imagemagick-200-lanczos.png
draw tests/data/wall-imagemagick-5-thick.png 24 30 4 '#404040' white 6 "$W5"
draw "$tmp/5.png" 18 14 1 black '#fffaf0' 4 "$W5"
"$CONVERT" "$tmp/5.png" -blur 0x1.0 tests/data/wall-imagemagick-5-blurred.png
