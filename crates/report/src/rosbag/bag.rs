//! A rosbag2 bag being written ([`RosBag`]): one MCAP file of profile `ros2` (schemas
//! `ros2msg`, messages `cdr`, each channel with its offered QoS and type hash) and the
//! bag's `metadata.yaml` (rosbag2 version 9), both built in memory; nothing reads the clock,
//! so one mission gives the same bytes.

use super::messages::RosType;
use super::wall::FRAME;
use crate::McapLogError;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Cursor;

/// The rosbag2 metadata version written.
const BAG_VERSION: u32 = 9;
/// The ROS 2 distribution whose message definitions the bag uses.
pub const ROS_DISTRO: &str = "kilted";

/// How a topic is offered: reliable, keep last `depth`; transient local (a late subscriber
/// gets the last messages) or volatile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Qos {
    /// History depth.
    pub depth: u32,
    /// Transient local durability (else volatile).
    pub latched: bool,
}

impl Qos {
    /// The profile as rosbag2 writes it (a YAML list of one profile, indented by `indent`).
    fn yaml(self, indent: &str) -> String {
        let durability = if self.latched {
            "transient_local"
        } else {
            "volatile"
        };
        let zero = "{sec: 0, nsec: 0}";
        format!(
            "{indent}- history: keep_last\n{indent}  depth: {}\n{indent}  reliability: reliable\n\
             {indent}  durability: {durability}\n{indent}  deadline: {zero}\n\
             {indent}  lifespan: {zero}\n{indent}  liveliness: automatic\n\
             {indent}  liveliness_lease_duration: {zero}\n\
             {indent}  avoid_ros_namespace_conventions: false\n",
            self.depth
        )
    }
}

/// One topic of the bag.
struct Topic {
    name: String,
    ty: RosType,
    qos: Qos,
    channel: u16,
    count: u64,
}

/// The two files of a bag: its `metadata.yaml` and its MCAP file, and the MCAP file's name.
#[derive(Clone, Debug)]
pub struct RosBagFiles {
    /// The file name of the MCAP file (`<bag>_0.mcap`).
    pub mcap_name: String,
    /// The MCAP file.
    pub mcap: Vec<u8>,
    /// `metadata.yaml`.
    pub metadata: String,
}

/// A bag being written: add its topics, then messages in time order, then [`RosBag::finish`].
pub struct RosBag {
    out: ::mcap::Writer<Cursor<Vec<u8>>>,
    name: String,
    schemas: BTreeMap<RosType, u16>,
    topics: Vec<Topic>,
    first_ns: Option<u64>,
    last_ns: u64,
}

/// A topic's handle in its bag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TopicId(usize);

impl RosBag {
    /// A bag named `name` (the folder's name: its MCAP file is `<name>_0.mcap`).
    pub fn new(name: &str) -> Result<Self, McapLogError> {
        let options = ::mcap::WriteOptions::new()
            .compression(None)
            .profile("ros2")
            .library(concat!("mason-report/", env!("CARGO_PKG_VERSION")));
        let out = options.create(Cursor::new(Vec::new()))?;
        Ok(RosBag {
            out,
            name: name.to_string(),
            schemas: BTreeMap::new(),
            topics: Vec::new(),
            first_ns: None,
            last_ns: 0,
        })
    }

    /// Adds topic `name` of type `ty`, offered with `qos`.
    pub fn topic(&mut self, name: &str, ty: RosType, qos: Qos) -> Result<TopicId, McapLogError> {
        let schema = match self.schemas.get(&ty) {
            Some(&id) => id,
            None => {
                let id = self
                    .out
                    .add_schema(ty.name(), "ros2msg", ty.definition().as_bytes())?;
                self.schemas.insert(ty, id);
                id
            }
        };
        let metadata = BTreeMap::from([
            ("offered_qos_profiles".to_string(), qos.yaml("")),
            ("topic_type_hash".to_string(), ty.hash().to_string()),
        ]);
        let channel = self.out.add_channel(schema, name, "cdr", &metadata)?;
        self.topics.push(Topic {
            name: name.to_string(),
            ty,
            qos,
            channel,
            count: 0,
        });
        Ok(TopicId(self.topics.len() - 1))
    }

    /// One message on `topic`, received at `ns` (nanoseconds; mission time).
    pub fn write(&mut self, topic: TopicId, ns: u64, cdr: &[u8]) -> Result<(), McapLogError> {
        let t = &mut self.topics[topic.0];
        t.count += 1;
        let header = ::mcap::records::MessageHeader {
            channel_id: t.channel,
            sequence: u32::try_from(t.count).unwrap_or(u32::MAX),
            log_time: ns,
            publish_time: ns,
        };
        self.out.write_to_known_channel(&header, cdr)?;
        self.first_ns = Some(self.first_ns.map_or(ns, |f| f.min(ns)));
        self.last_ns = self.last_ns.max(ns);
        Ok(())
    }

    /// Writes the MCAP file's summary (with the rosbag2 metadata record) and returns both files.
    pub fn finish(mut self) -> Result<RosBagFiles, McapLogError> {
        let mcap_name = format!("{}_0.mcap", self.name);
        let inner = self.metadata_body(&mcap_name, "");
        self.out.write_metadata(&::mcap::records::Metadata {
            name: "rosbag2".into(),
            metadata: BTreeMap::from([
                ("serialized_metadata".into(), inner),
                ("ROS_DISTRO".into(), ROS_DISTRO.into()),
            ]),
        })?;
        self.out.finish()?;
        let metadata = format!(
            "rosbag2_bagfile_information:\n{}",
            self.metadata_body(&mcap_name, "  ")
        );
        let mcap = self.out.into_inner().into_inner();
        Ok(RosBagFiles {
            mcap_name,
            mcap,
            metadata,
        })
    }

    /// The body of `rosbag2_bagfile_information`, each line indented by `indent`.
    fn metadata_body(&self, mcap_name: &str, indent: &str) -> String {
        let start = self.first_ns.unwrap_or(0);
        let duration = self.last_ns.saturating_sub(start);
        let total: u64 = self.topics.iter().map(|t| t.count).sum();
        let mut y = String::new();
        let _ = write!(
            y,
            "version: {BAG_VERSION}\nstorage_identifier: mcap\nduration:\n  nanoseconds: {duration}\n\
             starting_time:\n  nanoseconds_since_epoch: {start}\nmessage_count: {total}\n\
             topics_with_message_count:\n"
        );
        for t in &self.topics {
            let _ = write!(
                y,
                "  - topic_metadata:\n      name: {}\n      type: {}\n\
                 \x20     serialization_format: cdr\n      offered_qos_profiles:\n{}\
                 \x20     type_description_hash: {}\n    message_count: {}\n",
                t.name,
                t.ty.name(),
                t.qos.yaml("        "),
                t.ty.hash(),
                t.count
            );
        }
        let _ = write!(
            y,
            "compression_format: \"\"\ncompression_mode: \"\"\nrelative_file_paths:\n  - {mcap_name}\n\
             files:\n  - path: {mcap_name}\n    starting_time:\n      nanoseconds_since_epoch: {start}\n\
             \x20   duration:\n      nanoseconds: {duration}\n    message_count: {total}\n\
             custom_data:\n  frame: {FRAME}\n  time: mission time (0 = mission start)\n\
             ros_distro: {ROS_DISTRO}\n"
        );
        y.lines().map(|l| format!("{indent}{l}\n")).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metadata_counts_every_topic_and_spans_the_messages() {
        let mut bag = RosBag::new("b").unwrap();
        let pose = bag
            .topic(
                "/p",
                RosType::PoseStamped,
                Qos {
                    depth: 10,
                    latched: false,
                },
            )
            .unwrap();
        let wall = bag
            .topic(
                "/w",
                RosType::MarkerArray,
                Qos {
                    depth: 1,
                    latched: true,
                },
            )
            .unwrap();
        bag.write(pose, 5, b"\0\x01\0\0").unwrap();
        bag.write(wall, 7, b"\0\x01\0\0").unwrap();
        bag.write(pose, 9, b"\0\x01\0\0").unwrap();
        let files = bag.finish().unwrap();
        assert_eq!(files.mcap_name, "b_0.mcap");
        let m = &files.metadata;
        assert!(m.contains("  duration:\n    nanoseconds: 4\n"), "{m}");
        assert!(m.contains("nanoseconds_since_epoch: 5\n"));
        assert!(m.contains("  message_count: 3\n"));
        assert!(m.contains("        name: /p\n"));
        assert!(m.contains("      message_count: 2\n"));
        assert!(
            m.contains("            durability: transient_local\n"),
            "{m}"
        );
        assert!(files.mcap.starts_with(b"\x89MCAP0\r\n"));
    }
}
