#!/usr/bin/python3
"""Nothing lost, part 2 (issue 29): one check per class of the hostile-input
harness. Directory outputs never hold an input; a full disk, a file-size limit
or a full standard output is exit 4 with one `error:` line and nothing under
the final name; a damaged HDF5 file or an impossible image size never takes
flag-sim down; FIFOs and endless files are refused before any work; signals,
odd arguments and stale locks are handled as the contract says.

Run as: nothing_lost_test.py FLAG_SIM [CLASS ...] (no class: all of them)."""
import json
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

flag_sim = sys.argv[1]
only = set(sys.argv[2:])
failures = []
ASAN = "ASAN_OPTIONS" in os.environ

TINY = ('[scene]\nname = "tiny"\nmode = "hybrid"\nduration = 0.1\n'
        '[flag]\nsize = [1.5, 1.0]\nfine = [17, 25]\ncoarse = [9, 13]\n[gravity]\n')


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


def run(args, cwd, limit_fsize=None, limit_as=None, stdout=None, timeout=120):
    def limits():
        if limit_fsize is not None:  # flag-sim itself must not die of SIGXFSZ: default action kept
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_fsize, limit_fsize))
        if limit_as is not None and not ASAN:
            resource.setrlimit(resource.RLIMIT_AS, (limit_as, limit_as))
    return subprocess.run([flag_sim, *args], cwd=cwd, timeout=timeout, preexec_fn=limits,
                          stdout=stdout if stdout is not None else subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, errors="replace")


def tree(cwd):
    found = set()
    for root, dirs, files in os.walk(cwd):
        for name in dirs + files:
            found.add(os.path.relpath(os.path.join(root, name), cwd))
    return found


def one_error(r, code, what, words=None):
    ok = check(r.returncode == code, f"{what}: exit {r.returncode}, expected {code}\n{r.stderr}")
    ok &= check(r.stderr.startswith("error: ") and r.stderr.count("\n") == 1,
                f"{what}: not one error line\n{r.stderr[:2000]}")
    if words:
        ok &= check(words in r.stderr, f"{what}: '{words}' not in\n{r.stderr}")
    return ok


def read(path):
    with open(path, "rb") as f:
        return f.read()


def wanted(name):
    return not only or name in only


with tempfile.TemporaryDirectory() as base:
    good = os.path.join(base, "good.h5")
    r = subprocess.run([flag_sim, "run", "--quiet", "-o", good, "--frames", "4", "--set",
                        "flag.fine=[17,25]", "--set", "flag.coarse=[9,13]"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr

    def fresh(name):
        d = os.path.join(base, name)
        os.makedirs(d)
        shutil.copy(good, os.path.join(d, "good.h5"))
        with open(os.path.join(d, "s.toml"), "w") as f:
            f.write(TINY)
        return d

    # 1. Directory outputs: every file a directory output will write is an output.
    if wanted("directory_outputs"):
        d = fresh("dirs")
        os.makedirs(os.path.join(d, "fr"))
        os.makedirs(os.path.join(d, "objs"))
        shutil.copy(good, os.path.join(d, "fr/frame_00000.png"))   # an HDF5 file, PNG-named
        shutil.copy(good, os.path.join(d, "fr/frame_00002.png"))
        shutil.copy(good, os.path.join(d, "objs/frame_00001.obj"))
        subprocess.run([flag_sim, "render", "good.h5", "-o", "tex/", "--frames", "1:2"], cwd=d,
                       capture_output=True, check=True)
        shutil.copy(os.path.join(d, "tex/frame_00001.png"), os.path.join(d, "fr/frame_00001.png"))
        shutil.rmtree(os.path.join(d, "tex"))
        shutil.copy(os.path.join(d, "s.toml"), os.path.join(d, "fr/frame_00003.png"))
        before = {p: read(os.path.join(d, p)) for p in tree(d) if os.path.isfile(os.path.join(d, p))}
        cases = [
            ["render", "fr/frame_00000.png", "-o", "fr/"],
            ["render", "fr/frame_00002.png", "-o", "fr/", "--frames", "1:4"],
            ["render", "good.h5", "-o", "./fr", "--style", "textured", "--texture",
             "fr/frame_00001.png"],
            ["export", "objs/frame_00001.obj", "-o", "objs/"],
            ["export", "objs/frame_00001.obj", "-o", "./objs//", "--frames", "0:3"],
            ["run", "fr/frame_00003.png", "-o", "o.h5", "--render", "fr/"],
        ]
        for args in cases:
            one_error(run(args, d), 2, " ".join(args), "would overwrite")
            after = {p: read(os.path.join(d, p)) for p in tree(d)
                     if os.path.isfile(os.path.join(d, p))}
            check(after == before, f"{' '.join(args)}: files changed: "
                  f"{set(after) ^ set(before) or [p for p in after if after[p] != before[p]]}")

    # 2, 4, 7. A full disk, as a file-size limit makes it: exit 4, nothing under the final
    # name and no .partial; flag-sim is never killed by SIGXFSZ.
    if wanted("disk_full"):
        d = fresh("full")
        subprocess.run([flag_sim, "sweep", "s.toml", "--coarse", "9x13", "--point", "1", "-o",
                        "p.csv", "--quiet"], cwd=d, capture_output=True, check=True)
        cases = [
            (["compare", "s.toml", "--frames", "3", "-o", "c.csv"], 100),
            (["sweep", "s.toml", "--coarse", "9x13", "--frames", "3", "-o", "sw.csv", "--quiet"],
             100),
            (["sweep", "--merge", "p.csv", "-o", "m.csv"], 100),
            (["render", "good.h5", "-o", "v.mp4", "--size", "320x240"], 200),
            (["render", "good.h5", "-o", "v.gif", "--size", "320x240"], 200),
            (["render", "good.h5", "-o", "fr/", "--size", "320x240"], 2000),
            (["plot", "good.h5", "-o", "p.png"], 2000),
            (["export", "good.h5", "-o", "e.pc2"], 2000),
            (["export", "good.h5", "-o", "objs/"], 2000),
            (["sweep", "s.toml", "--coarse", "9x13", "--frames", "3", "--point", "1", "-o",
              "q.csv", "--reference-file", "r.rec"], 2000),
            (["sweep", "s.toml", "--coarse", "9x13", "--slurm", "batch", "-o", "b.csv"], 100),
            (["run", "s.toml", "-o", "o.h5", "--quiet"], 1000),
        ]
        for args, size in cases:
            before = tree(d)
            r = run(args, d, limit_fsize=size)
            one_error(r, 4, f"{' '.join(args)} under a {size}-byte file size limit")
            check(tree(d) == before, f"{' '.join(args)}: left {tree(d) - before}")
        # frames written before the disk filled are kept (render's PNGs, export's OBJs)
        r = run(["render", "good.h5", "-o", "fr/", "--size", "64x48"], d, limit_fsize=3000)
        made = tree(d) - before
        if check(r.returncode in (0, 4), f"render of small frames: exit {r.returncode}"):
            check(all(p.startswith("fr") and not p.endswith(".partial") for p in made),
                  f"render to fr/ under a limit left {made}")

    # 3. Standard output full.
    if wanted("stdout_full"):
        d = fresh("stdout")
        for args in (["info", "good.h5"], ["info", "--json", "good.h5"], ["scene", "s.toml"],
                     ["validate", "s.toml"], ["sweep", "s.toml", "--list", "--coarse", "9x13"],
                     ["--version"], ["help"], ["run", "s.toml", "-o", "o.h5", "--quiet"]):
            with open("/dev/full", "w") as full:
                r = run(args, d, stdout=full)
            one_error(r, 4, f"{' '.join(args)} >/dev/full", "standard output")

    # 5. A damaged file never takes flag-sim down: bits flipped in the first 4 KiB.
    if wanted("damaged_files"):
        d = fresh("damaged")
        pristine = bytearray(read(good))
        outcomes = {}
        # 60 variants; with today's HDF5 (1.10.8) three of them crash an unguarded
        # reader: seed 29 #24 (render), seed 30 #12 and #34 (info, render, export).
        variants = [(seed, n) for seed, count in ((29, 25), (30, 35)) for n in range(count)]
        rngs = {29: random.Random(29), 30: random.Random(30)}
        for seed, n in variants:
            data = bytearray(pristine)
            for _ in range(20):
                bit = rngs[seed].randrange(min(4096, len(data)) * 8)
                data[bit // 8] ^= 1 << (bit % 8)
            with open(os.path.join(d, "bad.h5"), "wb") as f:
                f.write(data)
            for args in (["info", "bad.h5"], ["info", "--json", "bad.h5"],
                         ["export", "bad.h5", "-o", "e.pc2"],
                         ["render", "bad.h5", "-o", "fr/", "--size", "64x48", "--frames", "0:1"]):
                r = run(args, d)
                outcomes[r.returncode] = outcomes.get(r.returncode, 0) + 1
                if r.returncode != 0:
                    one_error(r, 2, f"damaged file {seed} #{n}: {' '.join(args)}")
                elif args[1] == "--json":
                    try:
                        json.loads(r.stdout)
                    except ValueError as e:
                        check(False, f"damaged file {seed} #{n}: info --json does not parse: {e}")
            for name in ("e.pc2", "e.obj", "fr"):
                path = os.path.join(d, name)
                if os.path.isdir(path):
                    shutil.rmtree(path)
                elif os.path.exists(path):
                    os.remove(path)
        print("damaged files: exit codes", outcomes)
        # These 20 flips make HDF5 1.10.8 loop for ever in a read render makes: the test
        # read is given up after 60 s, exit 2 (the first 4 KiB of good.h5 are the same
        # bytes in every run of this scene).
        # Found again on 2026-12-05, when /checkpoint changed the file's layout.
        flips = [(93, 64), (164, 4), (174, 1), (181, 32), (492, 2), (496, 2), (1091, 32),
                 (2057, 2), (2284, 128), (2482, 1), (2579, 8), (2723, 8), (2776, 4), (2888, 4),
                 (2891, 1), (3024, 2), (3084, 8), (3401, 8), (3819, 16), (4010, 1)]
        data = bytearray(pristine)
        for offset, mask in flips:
            data[offset] ^= mask
        with open(os.path.join(d, "loop.h5"), "wb") as f:
            f.write(data)
        try:
            r = run(["render", "loop.h5", "-o", "fr/", "--size", "64x48"], d, timeout=120)
            one_error(r, 2, "a file that makes HDF5 loop", "damaged")
        except subprocess.TimeoutExpired:
            check(False, "a file that makes HDF5 loop: render still running after 120 s")
        # A damaged checkpoint: run --resume continues, or says why not; it never
        # crashes and never leaves an output behind.
        rng = random.Random(31)
        resumed = {}
        for n in range(20):
            data = bytearray(pristine)
            for _ in range(20):  # anywhere: /checkpoint's data lies past the first 4 KiB
                bit = rng.randrange(len(data) * 8)
                data[bit // 8] ^= 1 << (bit % 8)
            with open(os.path.join(d, "bad.h5"), "wb") as f:
                f.write(data)
            r = run(["run", "--resume", "bad.h5", "--frames", "6", "-o", "more.h5", "--quiet"], d)
            resumed[r.returncode] = resumed.get(r.returncode, 0) + 1
            if r.returncode != 0:  # a checksum guards every part: damage is refused
                one_error(r, 2, f"damaged checkpoint #{n}: run --resume")
                for left in ("more.h5", "more.h5.partial", "more.xdmf"):
                    check(not os.path.exists(os.path.join(d, left)),
                          f"damaged checkpoint #{n}: a refused resume left {left}")
            for left in ("more.h5", "more.xdmf"):
                if os.path.exists(os.path.join(d, left)):
                    os.remove(os.path.join(d, left))
        print("damaged checkpoints: run --resume exit codes", resumed)

    # 6. An image that does not fit in memory is one error line, not a crash.
    if wanted("render_memory") and not ASAN:
        d = fresh("memory")
        r = run(["render", "good.h5", "-o", "fr/", "--size", "4096x4096", "--frames", "0:1"], d,
                limit_as=300 << 20)
        check(r.returncode in (2, 4) and r.stderr.startswith("error: ")
              and r.stderr.count("\n") == 1,
              f"render 4096x4096 under 300 MiB: exit {r.returncode}\n{r.stderr}")
        check(tree(d) == {"good.h5", "s.toml"}, f"render under 300 MiB left {tree(d)}")

    # 8, 9. Non-regular files and endless files: refused before any work, quickly.
    if wanted("fifos"):
        d = fresh("fifos")
        subprocess.run([flag_sim, "sweep", "s.toml", "--coarse", "9x13", "--point", "1", "-o",
                        "p.csv", "--quiet"], cwd=d, capture_output=True, check=True)
        for name in ("v.gif", "t.png", "m.csv", "r.rec", "o.xdmf", "o.h5.partial", "c.csv"):
            os.mkfifo(os.path.join(d, name))
        os.makedirs(os.path.join(d, "fr"))
        os.mkfifo(os.path.join(d, "fr/frame_00000.png"))
        os.makedirs(os.path.join(d, "batch"))
        os.mkfifo(os.path.join(d, "batch/reference.sbatch"))
        with open(os.path.join(d, "sparse.csv"), "wb") as f:
            f.truncate(4 << 30)
        cases = [
            (["render", "good.h5", "-o", "v.gif"], "FIFO"),
            (["render", "good.h5", "-o", "x/", "--style", "textured", "--texture", "t.png"],
             "FIFO"),
            (["sweep", "--merge", "m.csv", "-o", "n.csv"], "FIFO"),
            (["sweep", "--merge", "/dev/zero", "-o", "n.csv"], "device"),
            (["sweep", "--merge", "sparse.csv", "-o", "n.csv"], "more than flag-sim reads"),
            (["sweep", "s.toml", "--coarse", "9x13", "--point", "1", "-o", "q.csv",
              "--reference-file", "r.rec"], "FIFO"),
            (["run", "s.toml", "-o", "o.h5"], "FIFO"),
            (["render", "good.h5", "-o", "fr/"], "FIFO"),
            (["compare", "s.toml", "-o", "c.csv"], "FIFO"),
            (["sweep", "s.toml", "--coarse", "9x13", "--slurm", "batch", "-o", "b.csv"], "FIFO"),
        ]
        for args, words in cases:
            before = tree(d)
            start = time.monotonic()
            try:
                r = run(args, d, timeout=30)
            except subprocess.TimeoutExpired:
                check(False, f"{' '.join(args)}: still waiting after 30 s")
                continue
            one_error(r, 2, " ".join(args), words)
            check(time.monotonic() - start < 10, f"{' '.join(args)}: took {time.monotonic() - start:.1f} s")
            check(tree(d) == before, f"{' '.join(args)}: left {tree(d) - before}")
        # existing directories where a file goes: exit 2 before the work
        for name in ("e.obj", "p.png", "w.xdmf"):
            os.makedirs(os.path.join(d, name))
        for args in (["export", "good.h5", "-o", "e.obj"], ["plot", "good.h5", "-o", "p.png"],
                     ["run", "s.toml", "-o", "w.h5"]):
            one_error(run(args, d), 2, " ".join(args), "directory")

    # 10. Unbounded work is refused with the number.
    if wanted("unbounded_work"):
        d = fresh("work")
        start = time.monotonic()
        r = run(["run", "s.toml", "-o", "o.h5", "--set", "flag.size=[1e-6,1e-6]"], d, timeout=60)
        one_error(r, 2, "a 1 um flag", "substeps a frame")
        check(not os.path.exists(os.path.join(d, "o.h5.partial")), "a 1 um flag left o.h5.partial")
        r = run(["validate", "s.toml", "--set", "flag.size=[1e-6,1e-6]"], d, timeout=60)
        check(r.returncode in (0, 2), f"validate of a 1 um flag: exit {r.returncode}")

    # 11. Signals: exit 130 and nothing half-written.
    if wanted("signals"):
        d = fresh("signals")
        p = subprocess.Popen([flag_sim, "plot", "good.h5", "-o", "p.png"], cwd=d,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(0.7)  # python is importing matplotlib
        p.send_signal(signal.SIGTERM)
        out, err = p.communicate(timeout=60)
        check(p.returncode in (0, 130), f"plot under SIGTERM: exit {p.returncode}\n{err}")
        check(not any(n.endswith(".partial.png") for n in os.listdir(d)),
              f"plot under SIGTERM left {os.listdir(d)}")
        p = subprocess.Popen([flag_sim, "run", "s.toml", "-o", "big.h5", "--quiet", "--set",
                              "flag.fine=[513,769]", "--set", "scene.mode=\"mass-spring\""], cwd=d,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(1.5)  # past the scene's parsing (then a signal is 130 in the set-up or after)
        p.send_signal(signal.SIGTERM)
        out, err = p.communicate(timeout=120)
        check(p.returncode == 130, f"run under SIGTERM in its set-up: exit {p.returncode}\n{err}")

    # 12. Messages and arguments.
    if wanted("arguments"):
        d = fresh("args")
        subprocess.run([flag_sim, "sweep", "s.toml", "--coarse", "9x13", "--point", "1", "-o",
                        "p.csv", "--quiet"], cwd=d, capture_output=True, check=True)
        # an output name that looks like an option is a file name to ffmpeg
        r = run(["render", "good.h5", "-o", "-y.gif", "--size", "64x48"], d)
        check(r.returncode == 0 and os.path.isfile(os.path.join(d, "-y.gif")),
              f"render -o -y.gif: exit {r.returncode}, files {os.listdir(d)}\n{r.stderr}")
        # a word in a numeric column
        lines = open(os.path.join(d, "p.csv")).read().splitlines()
        cells = lines[1].split(",")
        cells[9] = "sixty"
        with open(os.path.join(d, "w.csv"), "w") as f:
            f.write(lines[0] + "\n" + ",".join(cells) + "\n")
        one_error(run(["sweep", "--merge", "w.csv", "-o", "m.csv"], d), 2, "merge 'sixty'",
                  "not a number")
        # a 100,000-character name: one short line
        r = run(["export", "good.h5", "-o", "a" * 100000 + ".pc2"], d)
        one_error(r, 2, "a 100,000-character name", "too long")
        check(len(r.stderr) < 1000, f"a 100,000-character name: a {len(r.stderr)}-byte message")
        # a file's words reach the terminal without control characters, and JSON parses
        import h5py
        shutil.copy(good, os.path.join(d, "odd.h5"))
        with h5py.File(os.path.join(d, "odd.h5"), "r+") as f:
            f.attrs["status_reason"] = b"bad \x1b[31mred\x1b[0m \xff\xfe end"
        r = run(["info", "odd.h5"], d)
        check(r.returncode == 0 and "\x1b" not in r.stdout, f"info printed an escape: {r.stdout!r}")
        r = run(["info", "--json", "odd.h5"], d)
        try:
            reason = json.loads(r.stdout)["status_reason"]
            check("\x1b" in reason and "\ufffd" in reason, f"info --json reason {reason!r}")
        except ValueError as e:
            check(False, f"info --json of odd.h5 does not parse: {e}\n{r.stdout!r}")
        # empty and odd arguments
        for args in (["validate", ""], ["run", "s.toml", "-o", ""],
                     ["run", "s.toml", "--set", 'output.file=""'],
                     ["render", "good.h5", "-o", "fr/", "--frames", ""],
                     ["sweep", "s.toml", "--relax", "", "-o", "x.csv"],
                     ["sweep", "s.toml", "--backend=", "-o", "x.csv"],
                     ["sweep", "s.toml", "--slurm", "", "-o", "x.csv"],
                     ["run", "s.toml", "--frames", "0x10", "-o", "x.h5"],
                     ["compare", "s.toml", "--horizon", "0x1p-1", "-o", "x.csv"]):
            before = tree(d)
            one_error(run(args, d), 2, " ".join(repr(a) for a in args))
            check(tree(d) == before, f"{args}: left {tree(d) - before}")
        r = run(["help", "help"], d)
        check(r.returncode == 0 and "flag-sim" in r.stdout, f"help help: exit {r.returncode}")
        # a stale lock of a killed sweep is taken over
        os.makedirs(os.path.join(d, "sw.csv.points"))
        open(os.path.join(d, "sw.csv.points", ".lock"), "w").close()
        r = run(["sweep", "s.toml", "--coarse", "9x13", "--frames", "3", "--jobs", "2", "-o",
                 "sw.csv", "--quiet"], d, timeout=300)
        check(r.returncode == 0 and "taken over" in r.stderr,
              f"sweep over a stale points directory: exit {r.returncode}\n{r.stderr}")
        check(not os.path.exists(os.path.join(d, "sw.csv.points")), "points directory left")
        # one without a .lock is not a sweep's: refused, untouched
        os.makedirs(os.path.join(d, "sv.csv.points"))
        one_error(run(["sweep", "s.toml", "--coarse", "9x13", "--frames", "3", "--jobs", "2",
                       "-o", "sv.csv"], d), 2, "a foreign points directory", "not a sweep's")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
