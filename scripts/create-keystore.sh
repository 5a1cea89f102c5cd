#!/bin/bash
# Creates a DDS Security keystore for comply, laid out as ROS 2's SROS2 lays one out, so that
# `comply run --security`, `comply send --security` and ROS 2 nodes (ROS_SECURITY_KEYSTORE) can
# share it:
#
#   KEYSTORE/public/ca.cert.pem            the CA (identity and permissions CA in one)
#   KEYSTORE/private/ca.key.pem            its key: keep it off the robot
#   KEYSTORE/enclaves/governance.xml|.p7s  the domain's rules, signed by the CA
#   KEYSTORE/enclaves/<ENCLAVE>/           one per process: cert.pem, key.pem,
#       identity_ca.cert.pem, permissions_ca.cert.pem, governance.p7s,
#       permissions.xml, permissions.p7s
#
# The governance admits only authenticated participants and encrypts discovery, liveliness and
# every topic's data, on domains 0-230 (the range DDS Security admits). An enclave may name its
# role after '=': what its permissions let it publish and subscribe.
#   host      publishes state, diagnostics and the committed answers; subscribes the command,
#             chunk, request and committed_request topics
#   client    the reverse: commands the host, asks it, and reads what it publishes
#   monitor   reads what the host publishes only (a dashboard, a recorder): cannot command
#   all       every topic (the default)
# host, client and monitor also hold what every ROS 2 node publishes and reads besides its own
# topics (the graph's ros_discovery_info, rosout, parameter events, its parameter services), so
# an rclpy or rclcpp node runs under their enclaves too (ROS_SECURITY_ENCLAVE_OVERRIDE).
# Keys are ECDSA P-256, certificates valid for 10 years. Needs the openssl command line.
#
# Usage: scripts/create-keystore.sh KEYSTORE ENCLAVE[=ROLE]...
#   e.g.  scripts/create-keystore.sh ks /comply/host=host /comply/policy=client /comply/ui=monitor
# An existing CA in KEYSTORE is reused, so enclaves can be added later.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 KEYSTORE ENCLAVE[=ROLE]... (e.g. $0 keystore /comply/host=host /comply/client=client)" >&2
  exit 2
fi
command -v openssl >/dev/null || { echo "$0: needs openssl (apt-get install openssl)" >&2; exit 2; }
keystore=$1
shift
mkdir -p "$keystore/public" "$keystore/private" "$keystore/enclaves"
ca_cert=$keystore/public/ca.cert.pem
ca_key=$keystore/private/ca.key.pem
days=3650

if [ ! -f "$ca_cert" ]; then
  openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$ca_key" 2>/dev/null
  chmod 600 "$ca_key"
  openssl req -x509 -new -key "$ca_key" -subj "/CN=comply_security_ca" -days "$days" -sha256 \
    -out "$ca_cert"
  ln -sf ca.cert.pem "$keystore/public/identity_ca.cert.pem"
  ln -sf ca.cert.pem "$keystore/public/permissions_ca.cert.pem"
fi

sign() {  # sign XML P7S: S/MIME signed by the CA, as DDS Security reads governance and permissions
  openssl smime -sign -text -in "$1" -out "$2" -signer "$ca_cert" -inkey "$ca_key"
}

governance=$keystore/enclaves/governance.xml
if [ ! -f "$governance" ]; then
  cat >"$governance" <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>230</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>SIGN</rtps_protection_kind>
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
XML
  sign "$governance" "$keystore/enclaves/governance.p7s"
fi

# The topics a role publishes and subscribes, as <topic> elements (DDS names: rt/<host>/<topic>).
topics() {
  for topic in "$@"; do printf '<topic>rt/*/%s</topic>' "$topic"; done
}
commands=(cartesian_command joint_command cartesian_chunk joint_chunk request committed_request)
published=(state diagnostics committed)
# What a ROS 2 node (rcl) creates for itself, as DDS names: without it rcl cannot create the node.
parameter_services=(describe_parameters get_parameters get_parameter_types list_parameters
                    set_parameters set_parameters_atomically)
node_publish="<topic>ros_discovery_info</topic><topic>rt/rosout</topic>"
node_publish+="<topic>rt/parameter_events</topic>"
node_subscribe="<topic>ros_discovery_info</topic><topic>rt/parameter_events</topic>"
for service in "${parameter_services[@]}"; do
  node_publish+="<topic>rr/*/${service}Reply</topic>"
  node_subscribe+="<topic>rq/*/${service}Request</topic>"
done

for argument in "$@"; do
  enclave=${argument%%=*}
  role=all
  [ "$argument" != "$enclave" ] && role=${argument#*=}
  case $role in
    host) publish=$(topics "${published[@]}"); subscribe=$(topics "${commands[@]}") ;;
    client) publish=$(topics "${commands[@]}"); subscribe=$(topics "${published[@]}") ;;
    monitor) publish=""; subscribe=$(topics "${published[@]}") ;;
    all) publish="<topic>*</topic>"; subscribe="<topic>*</topic>" ;;
    *) echo "$0: role '$role' of $enclave is not one of host, client, monitor, all" >&2; exit 2 ;;
  esac
  if [ "$role" != all ]; then
    publish+=$node_publish
    subscribe+=$node_subscribe
  fi
  publish_rule="<publish><topics>$publish</topics></publish>"
  case $enclave in
    /*) ;;
    *) echo "$0: an enclave is a path from the root, such as /comply/host, not '$enclave'" >&2
       exit 2 ;;
  esac
  dir=$keystore/enclaves$enclave
  mkdir -p "$dir"
  # The subject is the enclave's path, as SROS2 names it; '/' is escaped for -subj.
  subject="/CN=${enclave//\//\\/}"
  openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$dir/key.pem" \
    2>/dev/null
  chmod 600 "$dir/key.pem"
  openssl req -new -key "$dir/key.pem" -subj "$subject" -out "$dir/request.csr"
  openssl x509 -req -in "$dir/request.csr" -CA "$ca_cert" -CAkey "$ca_key" -CAcreateserial \
    -days "$days" -sha256 -out "$dir/cert.pem" 2>/dev/null
  rm -f "$dir/request.csr"
  cp "$ca_cert" "$dir/identity_ca.cert.pem"
  cp "$ca_cert" "$dir/permissions_ca.cert.pem"
  cp "$keystore/enclaves/governance.p7s" "$dir/governance.p7s"
  not_before=$(date -u +%Y-%m-%dT%H:%M:%S)
  not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)
  cat >"$dir/permissions.xml" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$enclave">
      <subject_name>CN=$enclave</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        <domains><id_range><min>0</min><max>230</max></id_range></domains>
        $publish_rule
        <subscribe><topics>$subscribe</topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  sign "$dir/permissions.xml" "$dir/permissions.p7s"
  echo "$dir"
done
