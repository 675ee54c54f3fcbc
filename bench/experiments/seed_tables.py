"""The seed report's figures (shared/seed: section 10.1 and Appendix A), typed once, and the
rows its tables and ours share. Used by write_results.py."""

# The seed's tables (shared/seed, section 10.1 "Test Results – general" and Appendix A),
# None where it says N/A. Keys are run_report() columns.
SEED = {
    "general": dict(transmissions_sent=65, transmissions_received=65, successfully_matched=65, dropped=0,
                    false_positives=0, false_positive_rate_pct=0.00, success_rate_pct=100, sender_confirmed_rate_pct=100,
                    crc_accepted=65, crc_rejected=0, negative_confirmations_sent=0, error_catch_rate_pct=None,
                    response_time_avg_ms=887.26, response_time_min_ms=874, response_time_max_ms=1424,
                    latency_avg_ms=198.83, latency_min_ms=139, latency_max_ms=758),
    "noise": dict(transmissions_sent=65, transmissions_received=69, successfully_matched=64, dropped=1,
                  false_positives=1, false_positive_rate_pct=1.54, success_rate_pct=98.46, sender_confirmed_rate_pct=43.08,
                  crc_accepted=65, crc_rejected=4, negative_confirmations_sent=4, error_catch_rate_pct=80,
                  response_time_avg_ms=982.85, response_time_min_ms=926, response_time_max_ms=2711,
                  latency_avg_ms=278.78, latency_min_ms=222, latency_max_ms=496),
    "4m": dict(transmissions_sent=65, transmissions_received=65, successfully_matched=65, dropped=0,
               false_positives=0, false_positive_rate_pct=0.00, success_rate_pct=100, sender_confirmed_rate_pct=100,
               crc_accepted=65, crc_rejected=0, negative_confirmations_sent=0, error_catch_rate_pct=None,
               response_time_avg_ms=883.25, response_time_min_ms=867, response_time_max_ms=1344,
               latency_avg_ms=169.37, latency_min_ms=125, latency_max_ms=628),
    "7m": dict(transmissions_sent=65, transmissions_received=66, successfully_matched=65, dropped=0,
               false_positives=0, false_positive_rate_pct=0, success_rate_pct=100, sender_confirmed_rate_pct=100,
               crc_accepted=65, crc_rejected=1, negative_confirmations_sent=1, error_catch_rate_pct=100,
               response_time_avg_ms=886.31, response_time_min_ms=873, response_time_max_ms=1359,
               latency_avg_ms=134.83, latency_min_ms=82, latency_max_ms=643),
    "10m": dict(transmissions_sent=65, transmissions_received=77, successfully_matched=64, dropped=1,
                false_positives=0, false_positive_rate_pct=0, success_rate_pct=98.46, sender_confirmed_rate_pct=95.38,
                crc_accepted=64, crc_rejected=13, negative_confirmations_sent=13, error_catch_rate_pct=100,
                response_time_avg_ms=888.02, response_time_min_ms=876, response_time_max_ms=1350,
                latency_avg_ms=None, latency_min_ms=None, latency_max_ms=None),
}

# The rows of a condition's table, the seed's Appendix A rows and ours: (label, run_report
# column, kind); kind: n count, pct, ms. Columns the seed did not report show "–" in its column.
ROWS = [
    ("Total transmissions sent", "transmissions_sent", "n"),
    ("Frames played (retransmissions included)", "frame_attempts", "n"),
    ("Total transmissions received", "transmissions_received", "n"),
    ("Successfully matched", "successfully_matched", "n"),
    ("Dropped", "dropped", "n"),
    ("False positives", "false_positives", "n"),
    ("False positive rate", "false_positive_rate_pct", "pct"),
    ("Duplicates (a retransmission executed twice)", "duplicates", "n"),
    ("Success rate", "success_rate_pct", "pct"),
    ("Sender confirmed rate", "sender_confirmed_rate_pct", "pct"),
    ("CRC accepted", "crc_accepted", "n"),
    ("CRC rejected", "crc_rejected", "n"),
    ("Negative confirmations (NACKs) sent", "negative_confirmations_sent", "n"),
    ("Error catch rate", "error_catch_rate_pct", "pct"),
    ("Average response time", "response_time_avg_ms", "ms"),
    ("Min response time", "response_time_min_ms", "ms"),
    ("Max response time", "response_time_max_ms", "ms"),
    ("Average latency", "latency_avg_ms", "ms"),
    ("Min latency", "latency_min_ms", "ms"),
    ("Max latency", "latency_max_ms", "ms"),
]
