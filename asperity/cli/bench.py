def add_parser(sub):
    p = sub.add_parser("bench", help="(in progress)")
    p.set_defaults(func=lambda a: 0)
