import sys

from benchmarks.harness import main

if sys.argv[1:2] == ["pocket_sites"]:  # the binding-site benchmark alone (benchmarks/pocket_sites.py)
    from benchmarks import pocket_sites

    sys.exit(pocket_sites.main(sys.argv[2:]))
status = main()
_args = sys.argv[1:]
if not any(a in ("--list", "--worker", "-h", "--help") for a in _args) and all(
    a.startswith("-") or a.isdigit() for a in _args
):  # every case was run: the binding-site benchmark too
    from benchmarks import pocket_sites

    status = pocket_sites.main([]) or status
    from benchmarks import user_wait  # what a user waits for (issue 25, item 3)

    status = user_wait.main([]) or status
    from benchmarks import measure_peers  # the union measure on 1 and 2 threads and its peers (issue 25, item 1)

    status = measure_peers.main(["--threads", "2", "--out", "benchmarks/results/measure_peers_threads.json"]) or status
sys.exit(status)
