#!/usr/bin/env bash
# Creates the DDS Security PKI of a teleop deployment with openssl:
#   identity_ca.pem        identity CA: signs one identity certificate per node
#   permissions_ca.pem     permissions CA: signs the governance and every permissions document
#   governance.p7s         domain rules (S/MIME): authenticated participants only, access control
#                          on every topic, discovery, liveliness, submessages and payloads encrypted
#   <node>/identity.pem    the node's certificate (subject CN=<node>,O=teleop)
#   <node>/key.pem         its private key (unencrypted: the node reads it unattended; keep it 0600)
#   <node>/permissions.p7s what the node may publish and subscribe (S/MIME), nothing else
# for the nodes leader, follower and twin. CA keys stay in OUT_DIR/ca/: move them offline after use.
# --bench-identity adds bench_echo, the echo of teleop_roundtrip_bench (reads the leader's state,
# publishes the follower's): for benchmark PKIs only, never in a deployment.
#
# usage: scripts/make_pki.sh OUT_DIR [--days N] [--domains MIN-MAX] [--bench-identity]
set -euo pipefail

usage() { echo "usage: $0 OUT_DIR [--days N] [--domains MIN-MAX] [--bench-identity]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out=$1; shift
days=365
bench=0
domains=0-232
while [ $# -gt 0 ]; do
  case $1 in
    --days) days=${2:?}; shift 2 ;;
    --domains) domains=${2:?}; shift 2 ;;
    --bench-identity) bench=1; shift ;;
    *) usage ;;
  esac
done
[[ $days =~ ^[0-9]+$ ]] || { echo "make_pki: --days must be a number of days" >&2; exit 2; }
[[ $domains =~ ^([0-9]+)-([0-9]+)$ ]] || { echo "make_pki: --domains must be MIN-MAX" >&2; exit 2; }
domain_min=${BASH_REMATCH[1]}
domain_max=${BASH_REMATCH[2]}

# what each role may do; topic names as in transport/include/teleop/transport/topics.h
status=teleop/node_status
# the stop chain (docs/stop_chain.md): every node honours emergency stops; the operator station
# sends them (its device's button, `teleop estop|enable --config leader.yaml`)
estop=teleop/emergency_stop
# the operator station also sends resets (`teleop reset NODE --config leader.yaml`)
leader_publish="teleop/leader/joint_command teleop/leader/cartesian_command teleop/leader/joint_state teleop/hand/command teleop/tdpa/leader_to_follower teleop/reset $estop $status"
leader_subscribe="$estop teleop/follower/joint_state teleop/follower/wrench teleop/twin/feedback_torque teleop/twin/joint_state teleop/twin/contact_wrench/* teleop/twin/distances teleop/hand/state teleop/hand/joint_state teleop/tdpa/follower_to_leader $status"
follower_publish="teleop/follower/joint_state teleop/follower/wrench teleop/hand/state teleop/hand/joint_state teleop/tdpa/follower_to_leader $status"
follower_subscribe="$estop teleop/leader/joint_command teleop/leader/cartesian_command teleop/twin/joint_command teleop/hand/command teleop/tdpa/leader_to_follower teleop/reset $status"
twin_publish="teleop/twin/feedback_torque teleop/twin/joint_state teleop/twin/joint_command teleop/twin/contact_wrench/* teleop/twin/distances teleop/lockstep/state $status"
twin_subscribe="$estop teleop/leader/joint_state teleop/follower/joint_state teleop/follower/wrench teleop/hand/state teleop/lockstep/command $status"
bench_echo_publish="teleop/follower/joint_state"
bench_echo_subscribe="teleop/leader/joint_state"
nodes="leader follower twin"
[ "$bench" = 1 ] && nodes="$nodes bench_echo"

mkdir -p "$out/ca"
umask 077

new_key() { openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$1" 2>/dev/null; }

# self-signed CA: new_ca NAME SUBJECT
new_ca() {
  new_key "$out/ca/$1_key.pem"
  openssl req -x509 -new -sha256 -key "$out/ca/$1_key.pem" -days "$days" -subj "$2" \
    -addext "basicConstraints=critical,CA:TRUE" -addext "keyUsage=critical,keyCertSign,cRLSign,digitalSignature" \
    -out "$out/$1.pem"
}

# identity certificate signed by the identity CA: new_identity NODE
new_identity() {
  mkdir -p "$out/$1"
  new_key "$out/$1/key.pem"
  openssl req -new -sha256 -key "$out/$1/key.pem" -subj "/O=teleop/CN=$1" |
    openssl x509 -req -sha256 -days "$days" -CA "$out/identity_ca.pem" -CAkey "$out/ca/identity_ca_key.pem" \
      -set_serial "0x$(openssl rand -hex 8)" -out "$out/$1/identity.pem" 2>/dev/null
}

# S/MIME signature by the permissions CA: sign FILE.xml -> FILE.p7s
sign() {
  openssl smime -sign -text -in "$1.xml" -out "$1.p7s" \
    -signer "$out/permissions_ca.pem" -inkey "$out/ca/permissions_ca_key.pem"
}

# (no globbing: topic patterns such as teleop/twin/contact_wrench/* are for DDS, not the shell);
# every topic also in its per-arm form of a multi-arm robot, T/<arm> (transport/arm_topic.h)
topics_xml() { set -f; for t in $1; do printf '              <topic>%s</topic>\n              <topic>%s/*</topic>\n' "$t" "$t"; done; set +f; }

write_governance() {
  cat >"$out/governance.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>$domain_min</min><max>$domain_max</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
  sign "$out/governance"
}

# write_permissions NODE PUBLISH_TOPICS SUBSCRIBE_TOPICS
write_permissions() {
  local not_before not_after
  # a day of slack for hosts whose clocks run behind
  not_before=$(date -u -d "-1 day" +%Y-%m-%dT%H:%M:%S)
  not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)
  cat >"$out/$1/permissions.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$1">
      <subject_name>CN=$1,O=teleop</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        <domains><id_range><min>$domain_min</min><max>$domain_max</max></id_range></domains>
        <publish>
          <topics>
$(topics_xml "$2")
          </topics>
        </publish>
        <subscribe>
          <topics>
$(topics_xml "$3")
          </topics>
        </subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
  sign "$out/$1/permissions"
}

new_ca identity_ca "/O=teleop/CN=teleop identity CA"
new_ca permissions_ca "/O=teleop/CN=teleop permissions CA"
write_governance
for node in $nodes; do
  publish_var=${node}_publish
  subscribe_var=${node}_subscribe
  new_identity "$node"
  write_permissions "$node" "${!publish_var}" "${!subscribe_var}"
done
echo "make_pki: PKI for $nodes in $out (valid $days days, domains $domain_min-$domain_max)"
