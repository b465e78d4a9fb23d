"""rigid.Scene from several Python threads at once: loading (which derives the equations),
equations in every format, normal modes, code export and runs that write a report all reach the
symbolic core, which is guarded once inside the library; the GIL is released around runs and
reports, so these calls really overlap. Every thread must get what one thread alone gets."""
import pathlib
import re
import threading

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# short runs: what is tested is the sharing, not the length of a run
CASES = [
    ("physical_pendulum.toml", ["simulation.t_end=0.05", "simulation.output_dt=0.01"]),
    ("double_pendulum.toml", ["simulation.t_end=0.05", "simulation.output_dt=0.01"]),
    ("tennis_racket.toml", ["simulation.t_end=0.2"]),
]
ITERATIONS = 1000  # passes over one scene, all threads together
THREADS = 4

# the one entry of a report page that differs from run to run
_WALL = re.compile(r'"wall_time_s":[-+0-9.eE]+')


def _refusal(call):
    try:
        return call()
    except rigid.Error as e:
        return "refused: " + str(e)


def one_pass(case, page):
    """Everything one pass produces, as comparable values."""
    file, overrides = case
    scene = rigid.Scene(str(EXAMPLES / file), set=overrides)
    out = [scene.equations(format=f) for f in ("text", "latex", "json")]
    out.append(_refusal(lambda: str(scene.modes())))
    out.append(_refusal(lambda: scene.emit("c++")))
    out.append(_refusal(lambda: scene.emit("python")))
    run = scene.run(report=str(page))
    out.extend(run["columns"][name].tobytes() for name in sorted(run["columns"]))
    out.append(_WALL.sub("", page.read_text()))
    return out


def test_four_threads_match_one(tmp_path):
    serial = [one_pass(case, tmp_path / f"serial{k}.html") for k, case in enumerate(CASES)]
    failures, mismatches = [], []
    passes_per_thread = ITERATIONS // THREADS

    def worker(k):
        try:
            for i in range(passes_per_thread):
                j = (i + k) % len(CASES)
                if one_pass(CASES[j], tmp_path / f"t{k}.html") != serial[j]:
                    mismatches.append((k, i, CASES[j][0]))
        except Exception as e:  # noqa: BLE001 - reported by the assertion below
            failures.append(f"thread {k}: {type(e).__name__}: {e}")

    threads = [threading.Thread(target=worker, args=(k,)) for k in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []
    assert mismatches == []
