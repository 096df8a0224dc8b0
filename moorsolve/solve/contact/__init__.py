"""The berth: fenders, pile guides and hawsers in the problem (:mod:`.blocks`) and in the
Result (:mod:`.results`).
"""
