"""What Python adds to a run: tumble.simulate against the same simulate() call in C++
(build/release/bin/simulate_call), on the same scene files, interleaved, min and median of REPEATS.

  - batched: N = 10^5 bodies from a [[body_tables]] CSV, 100 RK4 steps (h = 1 ms), two samples of
    position: the Python-side overhead of the batched step (target: under 5 %);
  - one body: a single step of one body, the per-call overhead of simulate (microseconds).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_overhead.py [REPEATS] [N]
"""
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

import tumble

HERE = os.path.dirname(os.path.abspath(__file__))
CPP = os.environ.get("TUMBLE_SIMULATE_CALL", os.path.join(HERE, "..", "build", "release", "bin", "simulate_call"))
repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
N = int(sys.argv[2]) if len(sys.argv) > 2 else 100_000


def cpu():
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor()


def scenes(directory):
    rng = np.random.default_rng(1)
    table = os.path.join(directory, "bodies.csv")
    with open(table, "w") as f:
        f.write("name,mass,I1,I2,I3,wx,wy,wz\n")
        for i, w in enumerate(rng.normal(0, 10, (N, 3))):
            f.write(f"b{i},1.0,0.0108,0.0083,0.0042,{w[0]!r},{w[1]!r},{w[2]!r}\n")
    batched = os.path.join(directory, "batched.toml")
    with open(batched, "w") as f:
        f.write('[simulation]\nduration = 0.1\ntimestep = 1e-3\noutput_interval = 0.1\nintegrator = "rk4"\n'
                '[output]\nfields = ["position"]\n[world]\ngravity = [0, 0, -9.81]\n'
                '[[body_tables]]\nfile = "bodies.csv"\n')
    single = os.path.join(directory, "single.toml")
    with open(single, "w") as f:
        f.write('[simulation]\nduration = 1e-3\ntimestep = 1e-3\noutput_interval = 1e-3\n[output]\n'
                'fields = ["position"]\n[[bodies]]\nname = "box"\nshape = { type = "box", size = [0.1, 0.2, 0.3] }\n'
                'mass = 1.0\nangular_velocity = [1, 2, 3]\n')
    return batched, single


def cpp_times(scene, k):
    out = subprocess.run([CPP, scene, str(k)], check=True, capture_output=True, text=True).stdout
    return [float(x) for x in out.split()]


def python_times(scene, k):
    s = tumble.load_scene(scene)
    times = []
    for _ in range(k):
        start = time.perf_counter()
        tumble.simulate(s, threads=1)
        times.append(time.perf_counter() - start)
    return times


def main():
    if not os.path.exists(CPP):
        sys.exit(f"{CPP} is missing: build the release preset first (bash scripts/build.sh release)")
    print(f"# machine: {cpu()}, {os.cpu_count()} cores; python {platform.python_version()}, numpy {np.__version__}")
    print(f"# {repeats} interleaved repetitions; min and median seconds per simulate call")
    with tempfile.TemporaryDirectory() as d:
        batched, single = scenes(d)
        for label, scene, inner in ((f"batched N={N}, 100 rk4 steps", batched, 1),
                                    ("one body, one step", single, 2000)):
            cpp, py = [], []
            for _ in range(repeats):  # interleaved: C++ then Python, so drifts in load hit both
                cpp.append(min(cpp_times(scene, inner)))
                py.append(min(python_times(scene, inner)))
            c, p = np.array(cpp), np.array(py)
            print(f"{label}: C++ min {c.min():.6g} s median {np.median(c):.6g} s; Python min {p.min():.6g} s "
                  f"median {np.median(p):.6g} s; Python/C++ (median) {np.median(p) / np.median(c):.4f}, "
                  f"difference {1e6 * (np.median(p) - np.median(c)):.1f} us")


if __name__ == "__main__":
    main()
