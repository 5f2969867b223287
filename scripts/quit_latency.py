#!/usr/bin/env python3
"""Measures how long the explorer takes to end after `q`, Ctrl-C or SIGTERM while its worker is
busy (issue 24: "within 100 ms whatever the worker is doing").

Runs the release binary in a pseudo-terminal of 100x30, starts a long run (`auto` verifying a
long stiff run), waits, sends the key or signal and times the exit with waitpid (no polling).
Prints one line per trial and the median and maximum. Timing belongs here, not in the tests:
the machines are shared and noisy.

    cargo build --release && python3 scripts/quit_latency.py [BINARY] [TRIALS]
"""
import fcntl, os, pty, signal, statistics, struct, sys, termios, threading, time

BINARY = sys.argv[1] if len(sys.argv) > 1 else "target/release/rattleback"
TRIALS = int(sys.argv[2]) if len(sys.argv) > 2 else 10
# Busy cases: the rattleback verifying a long stiff run, and the pendulum resolving a small ε.
def busy_preset(name, replacements):
    """A shipped preset with some values replaced, written to a temporary file."""
    import subprocess, tempfile

    text = subprocess.run([BINARY, "presets", "show", name], capture_output=True, text=True, check=True).stdout
    for old, new in replacements:
        assert old in text, (name, old)
        text = text.replace(old, new)
    f = tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False)
    f.write(text)
    f.close()
    return ["--preset", f.name]


CASES = [
    ("rattleback k=1e5 t_end=1000", busy_preset("subcritical", [("k = 10000.0", "k = 100000.0"), ("t_end = 30.0", "t_end = 1000.0")])),
    ("pendulum eps=1e-4 t_end=1000", busy_preset("kapitza-upright", [("epsilon = 0.001", "epsilon = 0.0001"), ("t_end = 20.0", "t_end = 1000.0")])),
]
ENDINGS = [("q", b"q"), ("ctrl-c", b"\x03"), ("SIGTERM", signal.SIGTERM)]


def trial(args, how):
    pid, fd = pty.fork()
    if pid == 0:
        os.environ["TERM"] = "xterm-256color"
        os.execv(BINARY, [BINARY] + args)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    os.kill(pid, signal.SIGWINCH)
    # Drain the output so the child never blocks on a full pty.
    stop = threading.Event()

    def drain():
        while not stop.is_set():
            try:
                if not os.read(fd, 65536):
                    return
            except OSError:
                return

    t = threading.Thread(target=drain, daemon=True)
    t.start()
    time.sleep(1.0)
    os.write(fd, b" ")  # play
    time.sleep(1.5)
    start = time.perf_counter()
    if isinstance(how, bytes):
        os.write(fd, how)
    else:
        os.kill(pid, how)
    os.waitpid(pid, 0)
    took = time.perf_counter() - start
    stop.set()
    os.close(fd)
    return took


def main():
    rows = []
    for label, args in CASES:
        for name, how in ENDINGS:
            times = [trial(args, how) for _ in range(TRIALS)]
            rows.append((label, name, statistics.median(times), max(times)))
            print(f"{label:30} {name:8} median {1e3 * rows[-1][2]:6.1f} ms  max {1e3 * rows[-1][3]:6.1f} ms", flush=True)
    worst = max(r[3] for r in rows)
    print(f"worst of all: {1e3 * worst:.1f} ms")


if __name__ == "__main__":
    main()
