#!/usr/bin/env python3
# usage: sixteen_leg_urdf.py OCTOPOD_URDF OUT_URDF
# Sixteen legs: each of the octopod's legs twice, the copy 3 cm lower under new names. A
# robot inside mfp's caps that takes seconds to derive (tests/daemon_signals_test.sh,
# bench/sigterm_states.sh).
import re, sys
text = open(sys.argv[1]).read()
legs = sorted(set(re.findall(r'name="((?:left|right)\d)_coxa_yaw"', text)))
body_end = text.rindex("</robot>")
extra = []
for leg in legs:
    for block in re.findall(r'(<joint name="%s_[^"]*".*?</joint>|<link name="%s_[^"]*".*?</link>)' % (leg, leg), text, re.S):
        copy = block.replace('"%s_' % leg, '"%sb_' % leg)
        if '_coxa_yaw"' in block:
            copy = re.sub(r'<origin xyz="([^ ]+) ([^ ]+) ([^ "]+)"', lambda m: '<origin xyz="%s %s %g"' % (m.group(1), m.group(2), float(m.group(3)) - 0.03), copy, count=1)
        extra.append(copy)
open(sys.argv[2], "w").write(text[:body_end].replace('robot name="octopod"', 'robot name="sixteen"') + "\n".join(extra) + "\n</robot>\n")
