"""1000 renderers made and dropped: live GL objects and the process's RSS stay flat."""
import gc

import bounce

# Tiny renderers: the creations (shader programs linked, scene uploaded, G-buffer allocated) are
# what is measured, not the frames.
SIZE = 4
WARM_UP = 50
CREATIONS = 1000
# RSS after the warm-up may still grow by allocator pools and Mesa's shader cache settling; a leak of
# one renderer's CPU side (scene copy, pipeline, programs: tens of kB) per creation would add tens of
# MB over 1000. The bound comes from measurement (docs/python.md "Tests").
RSS_BOUND_BYTES = 8 * 1024 * 1024


def churn(scene, count):
    for i in range(count):
        r = bounce.Renderer(scene, "direct", SIZE, settings={"renderer.shadowMapSize": 64})
        if i % 50 == 0:
            r.frame(0)  # now and then a frame: its per-frame objects must go too
        if i % 2:
            r.close()   # half closed explicitly, half left to the garbage collector
        del r
    gc.collect()


def test_no_leak_across_1000_renderer_creations(gl):
    scene = bounce.Scene.load("cornell-box")
    churn(scene, WARM_UP)
    before = bounce.resources()
    churn(scene, CREATIONS)
    after = bounce.resources()
    for kind in ("gl_objects", "buffers", "textures", "framebuffers", "programs", "shaders", "queries",
                 "buffer_bytes", "texture_bytes"):
        assert after[kind] == before[kind], f"{kind}: {before[kind]} -> {after[kind]}"
    grown = after["rss_bytes"] - before["rss_bytes"]
    print(f"RSS {before['rss_bytes'] / 2**20:.1f} -> {after['rss_bytes'] / 2**20:.1f} MiB over {CREATIONS} renderers")
    assert grown < RSS_BOUND_BYTES, f"RSS grew {grown / 2**20:.1f} MiB over {CREATIONS} renderers"
