"""10,000 runs of one scene: resident memory flat (no result, graph or cache entry kept per run)."""
import os

import mechgraph

PAGE = os.sysconf("SC_PAGE_SIZE")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


def test_ten_thousand_runs_keep_memory_flat(scenes):
    scene = mechgraph.Scene.load(scenes / "valvetrain_cams.yaml")
    outputs = ["v_kurz.max_acceleration", "ta_kurz.time_area", "kurz.svaj"]

    def runs(n, offset):
        for i in range(n):
            r = scene.run(set={"rpm": f"{5000 + (i % 50)} rpm"}, outputs=outputs)  # 50 speeds over and over
            r["v_kurz.max_acceleration"]
            r["kurz.svaj"]

    runs(1000, 0)  # warm up: the memo cache holds its 50 speeds, allocators settle
    before = rss_bytes()
    runs(9000, 0)
    growth = rss_bytes() - before
    # A leak of one result per run (an svaj table of 361 x 5 doubles is ~14 kB) would be 126 MB here.
    assert growth < 8 * 2**20, f"resident memory grew {growth / 2**20:.1f} MiB over 9000 runs"
