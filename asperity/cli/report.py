def add_parser(sub):
    p = sub.add_parser("report", help="(in progress)")
    p.set_defaults(func=lambda a: 0)
