#!/usr/bin/env bash
# Issue 13's figures on a GPU through EGL, as one run of the device tool (a machine lent for minutes, not Debian 12,
# no package registry). Run from the repository root with, in the ignored folder .dev (tools/device/prepare.sh makes it):
#   deepgi.tar.xz              tools/device/pack.py .dev/deepgi.tar.xz (the binary and the libraries it loads)
#   scenes.tar.xz              CrytekSponza (its 3-channel textures as JPEG q92, to fit the transfer) and CornellBox
#   atrium_640_llvmpipe.exr    deepgi render --size 640x360 --frames 24 --set radiosity.resolution=quarter
#                              --set radiosity.interleave=4 (the software-GL defaults), made here with llvmpipe
#   hard_cache/                the hard suite's reference cache
#   fonts/DejaVuSans.ttf       the bench's labels (OpenImageIO finds it through OPENIMAGEIO_FONTS)
# and .gl (the glvnd debs, device README). Writes log.txt, figures.txt and a few images to $OUT.
# QUICK=1: tiny sizes and few frames, to try the script on llvmpipe's EGL. STEPS: which of the numbered steps run.
set -u
OUT=${OUT:-/tmp/gpu_out}
QUICK=${QUICK:-0}
STEPS=${STEPS:-12345}
step() { [[ $STEPS == *$1* ]]; }
mkdir -p "$OUT"
exec > >(tee -a "$OUT/log.txt") 2>&1
ROOT=$PWD
START=$SECONDS
BUDGET=${BUDGET:-420}  # seconds after which no new step starts
left() { [ $((SECONDS - START)) -lt "$BUDGET" ] || { echo "== out of time, skipping: $*"; return 1; }; }

if [ -d .gl ] && [ "$(id -u)" = 0 ] && [ "$QUICK" = 0 ]; then for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig; fi
D=/tmp/deepgi_pack
rm -rf $D && mkdir -p $D && tar xJf .dev/deepgi.tar.xz -C $D
export LD_LIBRARY_PATH=$D/lib OPENIMAGEIO_FONTS=$ROOT/.dev/fonts
G=$D/deepgi
# The binary's compiled-in folders: /work/main/{shaders,assets} and /work/shared/scenes.
if [ "$ROOT" != /work/main ]; then mkdir -p /work && rm -rf /work/main && ln -s "$ROOT" /work/main; fi
[ -e /work/shared/scenes/CrytekSponza/sponza.obj ] || { mkdir -p /work/shared/scenes && tar xJf .dev/scenes.tar.xz -C /work/shared/scenes; }
SPONZA=(/work/shared/scenes/CrytekSponza/sponza.obj --camera-file assets/views/crytek_sponza_atrium.json
        --set light.sun_azimuth=90 --set light.sun_elevation=70)

echo "== machine"; date -u; nproc; (nvidia-smi -L || true); uname -r
if ! $G render --context egl --size 64x36 --frames 2 --out /tmp/smoke; then
    echo "== EGL failed; naming NVIDIA's vendor file"
    export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
    $G render --context egl --size 64x36 --frames 2 --out /tmp/smoke || { echo "== no EGL context: stop"; exit 1; }
fi

if [ "$QUICK" = 1 ]; then S640=160x90 S720=160x90 S1080=192x108 FR=4; else S640=640x360 S720=1280x720 S1080=1920x1080 FR=64; fi

# render LABEL ARGS...: one `deepgi render`, its wall-clock frame, GPU pass sum and passes as one line of figures.txt.
render() {
    local label=$1; shift
    left "$label" || return 0
    if ! timeout 150 $G render --context egl --out "/tmp/r/$label" "$@" > "/tmp/r_$label.txt" 2>&1; then
        echo "== $label FAILED"; tail -5 "/tmp/r_$label.txt"; return 0
    fi
    python3 - "$label" "/tmp/r/$label/timings.json" <<'EOF' | tee -a "$OUT/figures.txt"
import json, sys
t = json.load(open(sys.argv[2]))
passes = " ".join(f"{p['pass'].replace(' ', '_')}={p['median_ms']:.3f}" for p in t["passes"])
print(f"{sys.argv[1]}\tframe_wall_ms={t['frame_median_ms']:.2f}\tgpu_passes_ms={t.get('gpu_passes_median_ms', 0):.3f}\t{passes}")
EOF
}

echo "== 1. the same frame as llvmpipe (its defaults at 360 rows: quarter resolution, interleave 4), 640x360, 24 frames"
if step 1 && left compare; then
    $G render --context egl --size 640x360 --frames 24 --set radiosity.resolution=quarter --set radiosity.interleave=4 \
        --out /tmp/r/same_as_cpu > /tmp/r_same.txt 2>&1 && $G compare /tmp/r/same_as_cpu/final.exr .dev/atrium_640_llvmpipe.exr
fi

echo "== 2. whole frames (GPU defaults: full-resolution radiosity, no interleave), $FR frames each"
step 2 && for sz in $S640 $S720 $S1080; do
    render "atrium_${sz}_default" --size $sz --frames $FR
    render "atrium_${sz}_direct" --size $sz --frames $FR --set radiosity.enabled=false
done
if step 2; then
    render "atrium_${S1080}_performance" --size $S1080 --frames $FR --preset performance
    render "atrium_${S1080}_quality" --size $S1080 --frames $FR --preset quality
    render "atrium_${S1080}_layer1" --size $S1080 --frames $FR --set gbuffer.layer2=false
    render "atrium_${S1080}_half" --size $S1080 --frames $FR --set radiosity.resolution=half
    render "atrium_${S1080}_probes_off" --size $S1080 --frames $FR --set probes.enabled=false
    render "atrium_${S1080}_ao" --size $S1080 --frames $FR --set ao.enabled=true
    for g in "predicted --set gbuffer.layer_routing=vertex" "predicted --set gbuffer.layer_routing=geometry" depth_peel; do
        render "heavy_${S1080}_${g%% *}_${g##*=}" assets/heavy/heavy.gltf --size $S1080 --frames $FR --set gbuffer.generation=$g
    done
    render "atrium_${S1080}_peel" --size $S1080 --frames $FR --set gbuffer.generation=depth_peel
    for sz in $S720 $S1080; do
        render "sponza_${sz}_default" "${SPONZA[@]}" --size $sz --frames $FR
        render "sponza_${sz}_direct" "${SPONZA[@]}" --size $sz --frames $FR --set radiosity.enabled=false
    done
fi
cp "/tmp/r/atrium_${S1080}_default/final.png" "$OUT/atrium_1080.png" 2>/dev/null
cp "/tmp/r/sponza_${S1080}_default/final.png" "$OUT/sponza_1080.png" 2>/dev/null

echo "== 3. the hard suite at scale 1, GPU defaults, cached references"
if step 3 && left hard; then
    if [ "$QUICK" = 1 ]; then H=(--hard-scenes furnace --frames 8 --one-bounce-frames 4); else H=(--hard-scenes offscreen_light,thin_wall,hidden_emitter,sun_patch,furnace); fi
    timeout 200 $G bench --context egl --suite hard --scales 1 --no-path --cache .dev/hard_cache --out /tmp/hard \
        --whole-frame-size 0x0 --quiet "${H[@]}" > /tmp/hard.txt 2>&1; echo "rc $?"; tail -40 /tmp/hard.txt
    cp /tmp/hard/results_hard.md "$OUT/hard_results.md" 2>/dev/null
fi

echo "== 4. the standard bench at $S1080: the paper's ratios with errors (64-spp references traced here)"
if step 4 && left bench; then
    if [ "$QUICK" = 1 ]; then B=(--spp 4 --frames 4 --timed-frames 2); else B=(--spp 64 --frames 24 --timed-frames 12); fi
    timeout 330 $G bench --context egl --size $S1080 --path-frames 0 --whole-frame-size 0x0 --quiet "${B[@]}" \
        --configs default,direct_only,layer1,two_layer_predicted,two_layer_peel,preset_performance,preset_quality,ao_same_taps,layer1_s19,layer1_s30,layer1_s50 \
        --out /tmp/bench > /tmp/bench.txt 2>&1; echo "rc $?"; tail -30 /tmp/bench.txt
    cp /tmp/bench/results.md "$OUT/bench_results.md" 2>/dev/null
    cp /tmp/bench/results.csv "$OUT/bench_results.csv" 2>/dev/null
fi
echo "== 5. where the gather's time goes on this GPU, $S1080"
if step 5; then
    render "gather_${S1080}_visibility0" --size $S1080 --frames $FR --set radiosity.visibility_steps=0
    render "gather_${S1080}_no_directional_fill" --size $S1080 --frames $FR --set probes.directional_fill=false
    render "gather_${S1080}_fill_only" --size $S1080 --frames $FR --set radiosity.samples=1 --set radiosity.visibility_steps=0
    render "gather_${S1080}_taps7" --size $S1080 --frames $FR --set radiosity.samples=7
    render "gather_${S1080}_layer1_vis0_nofill" --size $S1080 --frames $FR --set gbuffer.layer2=false \
        --set radiosity.visibility_steps=0 --set probes.directional_fill=false
fi
echo "== done in $((SECONDS - START)) s"
