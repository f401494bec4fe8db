"""``asperity serve``: the local web page (texture or scan -> friction law -> risk verdict)."""
from __future__ import annotations

from .parsing import DefaultsHelpFormatter


def add_parser(sub) -> None:
    from ..web.settings import DEFAULT_HOST, DEFAULT_MAX_UPLOAD_MB, DEFAULT_PORT
    p = sub.add_parser(
        "serve", help="a local web page: texture or scan -> friction law -> risk verdict",
        description="Start a web page on this machine: enter a wedge texture or upload a "
                    "scan, a mesh or a texture file and see its friction for every sliding "
                    "direction; fit a friction law and download it (gauge file, CSV, Abaqus); "
                    "slide a body on it; get the ratchet verdict of an assembly; run studies. "
                    "Long computations run in the background with a progress bar; uploads and "
                    "results are kept in the data folder and survive a restart. The page is "
                    "served on 127.0.0.1 only, unless --allow-remote; then every request needs "
                    "the access token printed at start. Open the printed link in a browser; "
                    "Ctrl-C stops the server.",
        formatter_class=DefaultsHelpFormatter)
    p.add_argument("--host", default=DEFAULT_HOST,
                   help="address to listen on; other than a loopback address only with "
                        "--allow-remote")
    p.add_argument("--port", type=int, default=DEFAULT_PORT,
                   help="port to listen on (0: a free one, printed at start)")
    p.add_argument("--data-dir", metavar="DIR", default=None,
                   help="folder of uploads and results (none given: "
                        "$XDG_DATA_HOME/asperity/web, else ~/.local/share/asperity/web)")
    p.add_argument("--allow-remote", action="store_true",
                   help="allow a non-loopback --host; every request then needs the access "
                        "token printed at start (?token=... sets a cookie)")
    p.add_argument("--max-upload", type=float, default=DEFAULT_MAX_UPLOAD_MB, metavar="MB",
                   help="largest request (upload) in MB")
    p.add_argument("--workers", metavar="N", default=None,
                   help="computations run at once, each in its own process (1 to 64; "
                        "none given: one per core; at most one per core and what the free "
                        "memory holds)")
    p.set_defaults(func=main)


def main(args) -> int:
    from ..errors import number_from_text
    from ..web.settings import make_settings
    workers = None if args.workers is None else number_from_text("--workers", args.workers)
    settings = make_settings(args.host, args.port, args.data_dir, args.allow_remote,
                             args.max_upload, workers)
    from ..web.server import serve
    return serve(settings)
