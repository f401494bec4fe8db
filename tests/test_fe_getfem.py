

@needs_getfem
def test_the_getfem_child_dies_with_its_parent(tmp_path):
    """SIGKILL the asperity process mid-run: its GetFEM child (a /usr/bin/python3) goes too."""
    import os
    import signal
    import subprocess
    import sys
    import time

    from asperity.lifeline import children_of
    root = __import__("pathlib").Path(__file__).resolve().parents[1]
    asm = _strip(tmp_path, dT=(0.0, 60.0), n=201)
    parent = subprocess.Popen([sys.executable, "-m", "asperity", "risk", str(asm), "--fe",
                               "getfem", "--fe-mesh", "4000", "-q"], cwd=root,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        child = None
        for _ in range(400):                               # up to 40 s to start GetFEM
            kids = [k for k in children_of(parent.pid) if _is_getfem(k)]
            if kids:
                child = kids[0]
                break
            assert parent.poll() is None, "the run ended before GetFEM started"
            time.sleep(0.1)
        assert child is not None, "no GetFEM child seen"
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        for _ in range(50):
            if not os.path.exists(f"/proc/{child}") or _zombie(child):
                break
            time.sleep(0.1)
        assert not os.path.exists(f"/proc/{child}") or _zombie(child), \
            "the GetFEM child outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait()


def _is_getfem(pid) -> bool:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return b"getfem_script.py" in fh.read()
    except OSError:
        return False


def _zombie(pid) -> bool:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        return True
